//! The learned policy and descriptions drawn on the map (the paper's Figure 4b).

use mdp::{Action, Overlay, Pos};

use crate::run::{RunReport, Setup};

/// The map as SVG with, for every state, its greedy action as an arrow, its description's
/// label in the corner and, on hover, the description's features; a legend lists every
/// description's features as `(dx, dy)=value`.
///
/// ```
/// use csql::{RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let report = csql::run_on(&setup, &settings);
/// let svg = csql::policy_svg(&setup, &report);
/// assert_eq!(svg.matches("<line").count(), 8); // one arrow per state
/// ```
pub fn policy_svg(setup: &Setup, report: &RunReport) -> String {
    let features = |label: u32| -> String {
        let d = &report.descriptions[label as usize];
        if d.features.is_empty() {
            "(no features: matches every state)".to_string()
        } else {
            d.features
                .iter()
                .map(|f| format!("({}, {})={}", f.dx, f.dy, f.value))
                .collect::<Vec<_>>()
                .join(" ")
        }
    };
    let mut o = Overlay {
        title: Some(format!(
            "{}: {} strategy, seed {}, {} descriptions{}",
            report.map,
            report.strategy,
            report.seed,
            report.descriptions.len(),
            if report.converged {
                ""
            } else {
                " (not converged)"
            }
        )),
        ..Overlay::default()
    };
    for s in &report.states {
        let p = Pos::new(s.row, s.col);
        if let Some(name) = s.greedy_action {
            let a = Action::ALL
                .into_iter()
                .find(|a| a.name() == name)
                .expect("reports name grid actions");
            o.arrow(p, a);
        }
        if let Some(label) = s.description {
            o.label(p, format!("d{label}"));
            o.tooltip(
                p,
                format!(
                    "row {}, col {}: d{label}, V = {:.4} (V* = {:.4})\n{}",
                    s.row,
                    s.col,
                    s.value.unwrap_or(0.0),
                    s.v_star,
                    features(label)
                ),
            );
        }
    }
    o.legend = report
        .descriptions
        .iter()
        .map(|d| format!("d{}: {}", d.label, features(d.label)))
        .collect();
    mdp::render_svg(&setup.map, &o)
}
