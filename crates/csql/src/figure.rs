//! The learned policy and descriptions drawn on the map (the paper's Figure 4b).

use mdp::{Action, Overlay, Pos};

use crate::run::{RunReport, Setup};

/// The map as SVG with, for every state, its greedy action as an arrow, its description's
/// label in the corner and, on hover, the description's features; a legend lists every
/// description's features as `(dx,dy)` followed by `E` (empty), `O` (obstacle) or `G` (goal).
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
    let features = |label: u32, short: bool| -> String {
        let d = &report.descriptions[label as usize];
        if d.features.is_empty() {
            return "(no features: matches every state)".to_string();
        }
        d.features
            .iter()
            .map(|f| {
                if short {
                    let code = match f.value {
                        "empty" => 'E',
                        "obstacle" => 'O',
                        _ => 'G',
                    };
                    format!("({},{}){code}", f.dx, f.dy)
                } else {
                    format!("({}, {})={}", f.dx, f.dy, f.value)
                }
            })
            .collect::<Vec<_>>()
            .join(" ")
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
                    features(label, false)
                ),
            );
        }
    }
    o.legend =
        vec!["Descriptions: (dx, dy) offset right and up, E empty, O obstacle, G goal".to_string()];
    o.legend.extend(
        report
            .descriptions
            .iter()
            .map(|d| format!("d{}: {}", d.label, features(d.label, true))),
    );
    mdp::render_svg(&setup.map, &o)
}
