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
            #[allow(
                clippy::expect_used,
                reason = "report names come from Action::name, so each names an action"
            )]
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

/// Every description of a run drawn as a small picture of what it senses around the
/// robot (the paper's Figure 4b shows such examples): the robot's cell is marked, each
/// sensed cell is coloured by the value the description requires (white empty, dark
/// obstacle, yellow goal) and cells it does not sense are left blank.
///
/// ```
/// use csql::{RunSettings, StrategyKind};
/// let report = csql::run(&RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1)).unwrap();
/// let svg = csql::descriptions_svg(&report);
/// assert_eq!(svg.matches("<g ").count(), report.descriptions.len());
/// ```
pub fn descriptions_svg(report: &RunReport) -> String {
    use std::fmt::Write as _;
    const CELL: i32 = 9;
    const COLUMNS: usize = 10;
    let reach = report
        .descriptions
        .iter()
        .flat_map(|d| &d.features)
        .map(|f| f.dx.abs().max(f.dy.abs()))
        .max()
        .unwrap_or(1)
        .max(1);
    let side = (2 * reach + 1) * CELL;
    let (panel_w, panel_h) = (side.max(60) + 16, side + 30);
    let rows = report.descriptions.len().div_ceil(COLUMNS);
    let width = panel_w * COLUMNS.min(report.descriptions.len().max(1)) as i32 + 16;
    let height = panel_h * rows as i32 + 56;
    let mut s = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif"><rect width="100%" height="100%" fill="white"/>"#
    );
    let _ = write!(
        s,
        r#"<text x="8" y="20" font-size="14">{}: the {} descriptions of the {} strategy, seed {}</text><text x="8" y="36" font-size="11">dN: K = description N, with K features; blue: the robot; white, dark, yellow: empty, obstacle, goal; blank: not sensed</text>"#,
        report.map,
        report.descriptions.len(),
        report.strategy,
        report.seed
    );
    for (i, d) in report.descriptions.iter().enumerate() {
        let (x0, y0) = (
            8 + (i % COLUMNS) as i32 * panel_w,
            48 + (i / COLUMNS) as i32 * panel_h,
        );
        let _ = write!(
            s,
            r#"<g transform="translate({x0},{y0})"><text x="{}" y="10" font-size="10" text-anchor="middle">d{}: {}</text>"#,
            side / 2,
            d.label,
            d.features.len()
        );
        let _ = write!(
            s,
            "<rect x=\"0\" y=\"14\" width=\"{side}\" height=\"{side}\" fill=\"white\" stroke=\"#ccc\"/>"
        );
        let cell_at = |dx: i32, dy: i32| ((dx + reach) * CELL, 14 + (reach - dy) * CELL);
        for f in &d.features {
            let (x, y) = cell_at(f.dx, f.dy);
            let fill = match f.value {
                "obstacle" => "#555555",
                "goal" => "#ffcc33",
                _ => "#ffffff",
            };
            let _ = write!(
                s,
                "<rect x=\"{x}\" y=\"{y}\" width=\"{CELL}\" height=\"{CELL}\" fill=\"{fill}\" stroke=\"#888\" stroke-width=\"0.6\"><title>({}, {}) = {}, cost {}</title></rect>",
                f.dx, f.dy, f.value, f.cost
            );
        }
        let (x, y) = cell_at(0, 0);
        let _ = write!(
            s,
            "<rect x=\"{x}\" y=\"{y}\" width=\"{CELL}\" height=\"{CELL}\" fill=\"#1f5fbf\"/></g>"
        );
    }
    s.push_str("</svg>\n");
    s
}
