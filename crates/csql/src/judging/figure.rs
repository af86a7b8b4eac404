//! The learned policy and descriptions drawn on the map (the paper's Figure 4b).

use mdp::{Action, Pos};

use crate::judging::report::{FeatureReport, RunReport, StateReport};
use crate::settings::setup::Setup;

/// The map as SVG with, for every state, its greedy action as an arrow and its
/// description's label in a band at the top of the cell, where no arrow reaches; a legend
/// beside the map. Hovering a cell shows its description's features; the list of every
/// description is a separate table ([`descriptions_table`]). Drawn in black, white and
/// greys, so it prints in grey.
///
/// ```
/// use csql::{RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let report = csql::run_on(&setup, &settings).unwrap();
/// let svg = csql::policy_svg(&setup, &report);
/// assert_eq!(svg.matches("class=\"arrow\"").count(), 8); // one arrow per state
/// ```
pub fn policy_svg(setup: &Setup, report: &RunReport) -> String {
    use std::fmt::Write as _;
    const CELL: f64 = 56.0;
    const BAND: f64 = 16.0;
    const TOP: f64 = 52.0;
    const LEFT: f64 = 12.0;
    let map = &setup.map;
    let (w, h) = (map.width() as f64 + 2.0, map.height() as f64 + 2.0);
    let legend_x = LEFT + w * CELL + 24.0;
    let width = legend_x + 210.0;
    let height = (TOP + h * CELL + 16.0).max(TOP + 230.0);
    let mut s = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif"><rect width="100%" height="100%" fill="white"/>"#
    );
    let _ = write!(
        s,
        r#"<text x="{LEFT}" y="22" font-size="17">{}: greedy policy and descriptions</text><text x="{LEFT}" y="41" font-size="13">{}, seed {}, {} descriptions{}</text>"#,
        escape(&report.map),
        report.learned_by(),
        report.seed,
        report.descriptions.len(),
        if report.converged {
            ""
        } else {
            ", not converged"
        }
    );
    let by_pos = |row: usize, col: usize| {
        report
            .states
            .iter()
            .find(|st| st.row == Some(row) && st.col == Some(col))
    };
    // Cells, with the border of obstacles around the interior.
    for r in 0..h as usize {
        for c in 0..w as usize {
            let (x, y) = (LEFT + c as f64 * CELL, TOP + r as f64 * CELL);
            let inside = r >= 1 && c >= 1 && r <= map.height() && c <= map.width();
            let cell = if inside {
                map.cell(Pos::new(r - 1, c - 1))
            } else {
                mdp::Cell::Obstacle
            };
            let fill = match cell {
                mdp::Cell::Obstacle => "#4d4d4d",
                mdp::Cell::Goal => "#d9d9d9",
                mdp::Cell::Empty => "#ffffff",
            };
            let _ = write!(
                s,
                "<rect x=\"{x:.1}\" y=\"{y:.1}\" width=\"{CELL}\" height=\"{CELL}\" fill=\"{fill}\" stroke=\"#999\" stroke-width=\"1\"/>"
            );
            if !inside {
                continue;
            }
            if cell == mdp::Cell::Goal {
                let _ = write!(
                    s,
                    r#"<text x="{:.1}" y="{:.1}" font-size="26" font-weight="bold" text-anchor="middle">G</text>"#,
                    x + CELL / 2.0,
                    y + CELL / 2.0 + 9.0
                );
            }
            let Some(st) = by_pos(r - 1, c - 1) else {
                continue;
            };
            if let Some(label) = st.description {
                let _ = write!(
                    s,
                    "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\" fill=\"#222\">d{label}<title>row {}, col {}: d{label}, V = {:.4} (V* = {:.4}): {}</title></text>",
                    x + 3.0,
                    y + BAND - 3.0,
                    row_of(st),
                    col_of(st),
                    st.value.unwrap_or(0.0),
                    st.v_star,
                    features_text(report, label)
                );
            }
            if let Some(a) = st.greedy_action.as_deref().and_then(action_named) {
                // The arrow lives below the label band: centre of the lower part.
                let (cx, cy) = (x + CELL / 2.0, y + BAND + (CELL - BAND) / 2.0);
                s.push_str(&arrow(cx, cy, a, (CELL - BAND) * 0.36, "arrow"));
            }
        }
    }
    // Legend.
    let lx = legend_x;
    let mut ly = TOP + 6.0;
    let _ = write!(
        s,
        r#"<text x="{lx:.1}" y="{ly:.1}" font-size="14" font-weight="bold">Legend</text>"#
    );
    ly += 26.0;
    s.push_str(&arrow(lx + 14.0, ly - 5.0, Action::Right, 12.0, "legend"));
    let _ = write!(
        s,
        r#"<text x="{:.1}" y="{ly:.1}" font-size="13">greedy action</text>"#,
        lx + 36.0
    );
    ly += 26.0;
    let _ = write!(
        s,
        r#"<text x="{lx:.1}" y="{ly:.1}" font-size="12">d7</text><text x="{:.1}" y="{ly:.1}" font-size="13">description of the state</text>"#,
        lx + 36.0
    );
    for (fill, text, mark) in [
        ("#4d4d4d", "obstacle or boundary", ""),
        ("#d9d9d9", "goal", "G"),
        ("#ffffff", "state (free cell)", ""),
    ] {
        ly += 26.0;
        let _ = write!(
            s,
            "<rect x=\"{lx:.1}\" y=\"{:.1}\" width=\"24\" height=\"18\" fill=\"{fill}\" stroke=\"#999\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\" font-weight=\"bold\" text-anchor=\"middle\">{mark}</text><text x=\"{:.1}\" y=\"{ly:.1}\" font-size=\"13\">{text}</text>",
            ly - 14.0,
            lx + 12.0,
            ly,
            lx + 36.0
        );
    }
    ly += 30.0;
    let _ = write!(
        s,
        r##"<text x="{lx:.1}" y="{ly:.1}" font-size="12" fill="#333">Features of each description:</text><text x="{lx:.1}" y="{:.1}" font-size="12" fill="#333">see the table beside this figure.</text>"##,
        ly + 16.0
    );
    s.push_str("</svg>\n");
    s
}

/// An arrow centred on `(cx, cy)` pointing along `a`, `half` long each side, in a group
/// of the given class.
fn arrow(cx: f64, cy: f64, a: Action, half: f64, class: &str) -> String {
    let (dx, dy) = match a {
        Action::Up => (0.0, -1.0),
        Action::Down => (0.0, 1.0),
        Action::Left => (-1.0, 0.0),
        Action::Right => (1.0, 0.0),
    };
    let (x1, y1) = (cx - dx * half, cy - dy * half);
    let (x2, y2) = (cx + dx * half, cy + dy * half);
    let head = half * 0.7;
    // Head: tip at (x2, y2), base across the direction.
    let (bx, by) = (x2 - dx * head, y2 - dy * head);
    let (px, py) = (-dy * head * 0.6, dx * head * 0.6);
    format!(
        "<g class=\"{class}\"><line x1=\"{x1:.1}\" y1=\"{y1:.1}\" x2=\"{bx:.1}\" y2=\"{by:.1}\" stroke=\"black\" stroke-width=\"3\"/><polygon points=\"{x2:.1},{y2:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"black\"/></g>",
        bx + px,
        by + py,
        bx - px,
        by - py
    )
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A description's features as `(dx, dy) value`, comma-separated.
/// A feature's offset on a grid (`(0, 0)` for a feature that has none).
fn offset(f: &FeatureReport) -> (i32, i32) {
    (f.dx.unwrap_or(0), f.dy.unwrap_or(0))
}

/// A feature as a reader knows it: its offset on a grid, its name elsewhere.
fn feature_label(f: &FeatureReport) -> String {
    match (&f.feature, f.dx, f.dy) {
        (Some(name), _, _) => name.clone(),
        (None, dx, dy) => format!("({}, {})", dx.unwrap_or(0), dy.unwrap_or(0)),
    }
}

/// A state as a reader knows it: `(row, col)` on a grid, its label elsewhere.
fn state_label(st: &StateReport) -> String {
    match &st.label {
        Some(label) => label.clone(),
        None => format!("({}, {})", row_of(st), col_of(st)),
    }
}

fn row_of(st: &StateReport) -> usize {
    st.row.unwrap_or(0)
}

fn col_of(st: &StateReport) -> usize {
    st.col.unwrap_or(0)
}

/// The grid action of a report's action name.
fn action_named(name: &str) -> Option<Action> {
    Action::ALL.into_iter().find(|a| a.name() == name)
}

fn features_text(report: &RunReport, label: u32) -> String {
    let d = &report.descriptions[label as usize];
    if d.features.is_empty() {
        return "no features: matches every state".to_string();
    }
    d.features
        .iter()
        .map(|f| format!("{} {}", feature_label(f), f.value))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Every description of a run as a Markdown table: its label, the states it describes
/// (`(row, column)` on a grid, the world's state labels elsewhere), its number of
/// features, their summed cost and the readings it requires (on a grid `(dx, dy) value`,
/// `dx` to the right and `dy` up from the robot; elsewhere `feature reading`).
///
/// ```
/// use csql::{RunSettings, StrategyKind};
/// let report = csql::run(&RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1)).unwrap();
/// let table = csql::descriptions_table(&report);
/// let rows = table.lines().filter(|l| l.starts_with("| d") && !l.starts_with("| description"));
/// assert_eq!(rows.count(), report.descriptions.len());
/// ```
pub fn descriptions_table(report: &RunReport) -> String {
    use std::fmt::Write as _;
    // Grid states have a row and column; the states of other worlds have labels.
    let grid = report.states.iter().all(|st| st.label.is_none());
    let (how, states) = if grid {
        (
            "Offsets `(dx, dy)` are measured from the robot, `dx` to the right and `dy` up; a description matches a state when every listed cell has the listed value.",
            "states (row, col)",
        )
    } else {
        (
            "A description matches a state when every listed feature has the listed reading.",
            "states",
        )
    };
    let mut s = format!(
        "# Descriptions: {}, {}, seed {}\n\n{how}\n\n| description | {states} | features | cost | readings required |\n|---|---|---|---|---|\n",
        report.map,
        report.learned_by(),
        report.seed
    );
    for d in &report.descriptions {
        let states: Vec<String> = report
            .states
            .iter()
            .filter(|st| st.description == Some(d.label))
            .map(state_label)
            .collect();
        let cost: f64 = d.features.iter().map(|f| f.cost).sum();
        let _ = writeln!(
            s,
            "| d{} | {} | {} | {cost:.0} | {} |",
            d.label,
            states.join(" "),
            d.features.len(),
            features_text(report, d.label)
        );
    }
    s
}

/// Every description of a run drawn as a small picture of what it senses around the
/// robot (the paper's Figure 4b shows such examples): the robot's cell is marked with a
/// black dot, each sensed cell is shaded by the value the description requires (white
/// empty, dark grey obstacle, light grey goal) and cells it does not sense are left blank.
/// Greys only, so it prints in grey.
///
/// ```
/// use csql::{RunSettings, StrategyKind};
/// let report = csql::run(&RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1)).unwrap();
/// let svg = csql::descriptions_svg(&report);
/// assert_eq!(svg.matches("<g ").count(), report.descriptions.len());
/// ```
pub fn descriptions_svg(report: &RunReport) -> String {
    use std::fmt::Write as _;
    const CELL: i32 = 11;
    const COLUMNS: usize = 10;
    let reach = report
        .descriptions
        .iter()
        .flat_map(|d| &d.features)
        .map(|f| offset(f).0.abs().max(offset(f).1.abs()))
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
        r#"<text x="8" y="20" font-size="14">{}: the {} descriptions of {}, seed {}</text><text x="8" y="36" font-size="11">dN: K = description N, with K features; black dot: the robot; white: empty; dark grey: obstacle; light grey: goal; blank: not sensed</text>"#,
        report.map,
        report.descriptions.len(),
        match report.settings.learner {
            crate::LearnerSettings::CsQl(_) => format!("the {}", report.learned_by()),
            _ => report.learned_by(),
        },
        report.seed
    );
    for (i, d) in report.descriptions.iter().enumerate() {
        let (x0, y0) = (
            8 + (i % COLUMNS) as i32 * panel_w,
            48 + (i / COLUMNS) as i32 * panel_h,
        );
        let _ = write!(
            s,
            r#"<g transform="translate({x0},{y0})"><text x="{}" y="10" font-size="11" text-anchor="middle">d{}: {}</text>"#,
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
            let (dx, dy) = offset(f);
            let (x, y) = cell_at(dx, dy);
            let fill = match f.value.as_str() {
                "obstacle" => "#555555",
                "goal" => "#bbbbbb",
                _ => "#ffffff",
            };
            let _ = write!(
                s,
                "<rect x=\"{x}\" y=\"{y}\" width=\"{CELL}\" height=\"{CELL}\" fill=\"{fill}\" stroke=\"#888\" stroke-width=\"0.6\"><title>({}, {}) = {}, cost {}</title></rect>",
                dx, dy, f.value, f.cost
            );
        }
        let (x, y) = cell_at(0, 0);
        let _ = write!(
            s,
            "<rect x=\"{x}\" y=\"{y}\" width=\"{CELL}\" height=\"{CELL}\" fill=\"white\" stroke=\"#888\" stroke-width=\"0.6\"/><circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"{:.1}\" fill=\"black\"/></g>",
            f64::from(x) + f64::from(CELL) / 2.0,
            f64::from(y) + f64::from(CELL) / 2.0,
            f64::from(CELL) * 0.32
        );
    }
    s.push_str("</svg>\n");
    s
}
