//! Figures: learning curves (plotters, with an embedded font so no system font is
//! needed), decision trees drawn as SVG, and side-by-side composition.

use std::path::Path;
use std::sync::Once;

use anyhow::{Result, anyhow};
use cslearn::{Branch, DecisionTree, Node, NodeId};
use csql::TracePoint;
use mdp::{Cell, Feature, FeatureSpace};
use plotters::prelude::*;

pub fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bytes are a valid TrueType font shipped by the dejavu crate.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

/// The learning curve of one strategy: per trial the mean, lowest and highest
/// cumulative sensing cost over runs, and the (trial, cost) where each run first became
/// sufficient and where it converged.
pub struct Curve {
    pub name: String,
    pub points: Vec<(f64, f64, f64)>,
    pub sufficient: Vec<(f64, f64)>,
    pub converged: Vec<(f64, f64)>,
}

impl Curve {
    /// The curve of a group of runs: their spread, and where each became sufficient and
    /// converged.
    pub fn of<R: std::borrow::Borrow<csql::RunReport>>(name: String, runs: &[R]) -> Curve {
        let traces: Vec<&[TracePoint]> = runs.iter().map(|r| r.borrow().trace.as_slice()).collect();
        let marks = |at: fn(&csql::Table1) -> Option<(u32, f64)>| {
            runs.iter()
                .filter_map(|r| at(&r.borrow().table1).map(|(t, c)| (f64::from(t), c)))
                .collect()
        };
        Curve {
            name,
            points: spread(&traces),
            sufficient: marks(|t| Some((t.trials_to_sufficient?, t.cost_to_sufficient?))),
            converged: marks(|t| Some((t.trials_to_converge?, t.cost_to_converge?))),
        }
    }
}

/// Mean, lowest and highest cumulative sensing cost at each trial over runs; a run that
/// has ended keeps its final cost.
pub fn spread(traces: &[&[TracePoint]]) -> Vec<(f64, f64, f64)> {
    let longest = traces.iter().map(|t| t.len()).max().unwrap_or(0);
    (0..longest)
        .map(|i| {
            let values: Vec<f64> = traces
                .iter()
                .filter_map(|t| t.get(i).or(t.last()).map(|p| p.cumulative_cost))
                .collect();
            let mean = values.iter().sum::<f64>() / values.len() as f64;
            let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (mean, lo, hi)
        })
        .collect()
}

/// Cumulative sensing cost against trials, one panel per strategy with its own scale:
/// the mean over runs as a black line, the lowest to highest run as a grey band, and for
/// each run an open circle where it became sufficient and a filled triangle where it
/// converged. Black and greys only, so it prints in grey.
pub fn learning_curves(path: &Path, title: &str, curves: &[Curve]) -> Result<()> {
    register_font();
    let plot_err = |e: &dyn std::fmt::Display| anyhow!("drawing {}: {e}", path.display());
    // Two panels a row for up to four curves; four a row (one per strategy) beyond.
    let (cols, (pw, ph)) = match curves.len() {
        0 | 1 => (1, (560_u32, 380_u32)),
        2..=4 => (2, (560, 380)),
        _ => (4, (420, 320)),
    };
    let rows = curves.len().div_ceil(cols).max(1);
    // Drawn into memory, then written through a temporary file and a rename.
    let mut svg = String::new();
    let base = SVGBackend::with_string(&mut svg, (pw * cols as u32, ph * rows as u32 + 50))
        .into_drawing_area();
    base.fill(&WHITE).map_err(|e| plot_err(&e))?;
    let root = base
        .titled(title, ("sans-serif", 22))
        .map_err(|e| plot_err(&e))?;
    let panels = root.split_evenly((rows, cols));
    let grey = RGBColor(170, 170, 170);
    for (i, (panel, curve)) in panels.iter().zip(curves).enumerate() {
        let trials = curve.points.len().max(2) as f64;
        let top = curve.points.iter().map(|p| p.2).fold(1.0, f64::max);
        let mut chart = ChartBuilder::on(panel)
            .caption(&curve.name, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(46)
            .y_label_area_size(78)
            .build_cartesian_2d(0.0..trials * 1.02, 0.0..top * 1.05)
            .map_err(|e| plot_err(&e))?;
        chart
            .configure_mesh()
            .x_desc("trial")
            .y_desc("cumulative sensing cost")
            .axis_desc_style(("sans-serif", 16))
            .label_style(("sans-serif", 14))
            .y_labels(6)
            .x_labels(6)
            .light_line_style(WHITE)
            .bold_line_style(RGBColor(230, 230, 230))
            .y_label_formatter(&|y| short(*y))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .draw()
            .map_err(|e| plot_err(&e))?;
        let x = |t: usize| (t + 1) as f64;
        let band: Vec<(f64, f64)> = curve
            .points
            .iter()
            .enumerate()
            .map(|(t, p)| (x(t), p.2))
            .chain(
                curve
                    .points
                    .iter()
                    .enumerate()
                    .rev()
                    .map(|(t, p)| (x(t), p.1)),
            )
            .collect();
        chart
            .draw_series(std::iter::once(Polygon::new(band, grey.mix(0.45))))
            .map_err(|e| plot_err(&e))?
            .label("lowest to highest run")
            .legend(move |(x, y)| {
                Rectangle::new([(x, y - 6), (x + 24, y + 6)], grey.mix(0.45).filled())
            });
        chart
            .draw_series(LineSeries::new(
                curve.points.iter().enumerate().map(|(t, p)| (x(t), p.0)),
                BLACK.stroke_width(2),
            ))
            .map_err(|e| plot_err(&e))?
            .label("mean over runs")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2)));
        chart
            .draw_series(
                curve
                    .sufficient
                    .iter()
                    .map(|&(t, c)| Circle::new((t, c), 6, BLACK.stroke_width(2))),
            )
            .map_err(|e| plot_err(&e))?
            .label("a run becomes sufficient")
            .legend(|(x, y)| Circle::new((x + 12, y), 6, BLACK.stroke_width(2)));
        chart
            .draw_series(
                curve
                    .converged
                    .iter()
                    .map(|&(t, c)| TriangleMarker::new((t, c), 7, BLACK.filled())),
            )
            .map_err(|e| plot_err(&e))?
            .label("a run converges")
            .legend(|(x, y)| TriangleMarker::new((x + 12, y), 7, BLACK.filled()));
        // One legend, in the first panel's empty upper left (above a rising curve), serves every panel.
        if i == 0 {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .background_style(WHITE.mix(0.9))
                .border_style(RGBColor(150, 150, 150))
                .label_font(("sans-serif", 14))
                .draw()
                .map_err(|e| plot_err(&e))?;
        }
    }
    root.present().map_err(|e| plot_err(&e))?;
    drop(panels);
    drop(root);
    drop(base);
    crate::files::write_atomic(path, svg)
}

/// A cost on an axis, in one style at every size: at most one decimal, none when it is
/// zero, and a suffix for thousands and millions (`250k`, `1.2M`, `1M`, `10M`).
pub fn short(y: f64) -> String {
    let (x, suffix) = if y >= 1e6 {
        (y / 1e6, "M")
    } else if y >= 1e3 {
        (y / 1e3, "k")
    } else {
        (y, "")
    };
    let text = format!("{x:.1}");
    let text = text.strip_suffix(".0").unwrap_or(&text);
    format!("{text}{suffix}")
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A decision tree over grid descriptions as SVG, drawn left to right so that it fits a
/// page's width: split nodes (boxes) name the sensed offset `(dx, dy)` from the robot,
/// edges the cell's value (E empty, O obstacle, G goal), leaves (rounded) the
/// description; a legend under the title says so. "Other" branches that lead to no
/// description are left out.
pub fn tree_svg(tree: &DecisionTree, space: &FeatureSpace, title: &str) -> String {
    const COL: f64 = 118.0;
    const ROW: f64 = 22.0;
    const TOP: f64 = 96.0;
    const LEFT: f64 = 16.0;
    fn drawn(tree: &DecisionTree, id: NodeId) -> bool {
        !matches!(tree.node(id), Node::Leaf { class: None, .. })
    }
    // Leaf order gives y; depth gives x.
    fn layout(
        tree: &DecisionTree,
        id: NodeId,
        depth: usize,
        next: &mut f64,
        pos: &mut Vec<(NodeId, f64, usize)>,
    ) -> f64 {
        let kids: Vec<NodeId> = tree
            .node(id)
            .children()
            .map(|c| c.1)
            .filter(|&c| drawn(tree, c))
            .collect();
        let y = if kids.is_empty() {
            *next += 1.0;
            *next - 1.0
        } else {
            let ys: Vec<f64> = kids
                .iter()
                .map(|&k| layout(tree, k, depth + 1, next, pos))
                .collect();
            (ys[0] + ys[ys.len() - 1]) / 2.0
        };
        pos.push((id, y, depth));
        y
    }
    let mut pos = Vec::new();
    let mut next = 0.0;
    layout(tree, tree.root(), 0, &mut next, &mut pos);
    pos.sort_by_key(|p| p.0);
    let at = |id: NodeId| {
        let p = pos.iter().find(|p| p.0 == id).expect("laid out");
        (LEFT + 40.0 + p.2 as f64 * COL, TOP + 12.0 + p.1 * ROW)
    };
    let depth = pos.iter().map(|p| p.2).max().unwrap_or(0);
    let width = (LEFT + 100.0 + depth as f64 * COL).max(480.0);
    let height = TOP + 24.0 + next.max(1.0) * ROW;
    let mut s = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif"><rect width="100%" height="100%" fill="white"/>"#
    );
    s.push_str(&format!(
        r#"<text x="{LEFT}" y="22" font-size="16">{}</text>"#,
        escape(title)
    ));
    s.push_str(&format!(
        "<rect x=\"{LEFT}\" y=\"34\" width=\"58\" height=\"16\" fill=\"#eeeeee\" stroke=\"black\"/><text x=\"{:.0}\" y=\"46\" font-size=\"11\" text-anchor=\"middle\">(dx, dy)</text><text x=\"{:.0}\" y=\"46\" font-size=\"12\">sense the cell dx right, dy up from the robot</text>\
         <rect x=\"{LEFT}\" y=\"54\" width=\"30\" height=\"16\" rx=\"8\" fill=\"white\" stroke=\"black\"/><text x=\"{:.0}\" y=\"66\" font-size=\"11\" text-anchor=\"middle\">d7</text><text x=\"{:.0}\" y=\"66\" font-size=\"12\">description 7</text>\
         <text x=\"{LEFT}\" y=\"86\" font-size=\"12\">edges: E empty, O obstacle, G goal, * any other value, ? not measured</text>",
        LEFT + 29.0,
        LEFT + 66.0,
        LEFT + 15.0,
        LEFT + 38.0,
    ));
    for &(id, _, _) in &pos {
        let (x, y) = at(id);
        for (branch, child) in tree.node(id).children() {
            if !drawn(tree, child) {
                continue;
            }
            let (cx, cy) = at(child);
            let label = match branch {
                Branch::Value(v) => match Cell::from_code(v.0) {
                    Some(Cell::Empty) => "E",
                    Some(Cell::Obstacle) => "O",
                    Some(Cell::Goal) => "G",
                    None => "?",
                },
                Branch::Missing => "?",
                Branch::Other => "*",
            };
            // An elbow: right from the parent, down or up, right into the child.
            let mid = x + 44.0;
            s.push_str(&format!(
                "<path d=\"M{:.1},{y:.1} H{mid:.1} V{cy:.1} H{:.1}\" fill=\"none\" stroke=\"#777\"/>",
                x + 30.0,
                cx - 26.0
            ));
            s.push_str(&format!(
                "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"11\" fill=\"#222\">{label}</text>",
                mid + 4.0,
                cy - 3.0
            ));
        }
    }
    for &(id, _, _) in &pos {
        let (x, y) = at(id);
        match tree.node(id) {
            Node::Split { feature, .. } => {
                let o = space.offset(Feature(feature.0));
                s.push_str(&format!(
                    "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"60\" height=\"18\" fill=\"#eeeeee\" stroke=\"black\"/><text x=\"{x:.1}\" y=\"{:.1}\" font-size=\"11\" text-anchor=\"middle\">({}, {})</text>",
                    x - 30.0,
                    y - 9.0,
                    y + 4.0,
                    o.dx,
                    o.dy,
                ));
            }
            Node::Leaf { class, .. } => {
                let label = class.map_or("none".to_string(), |c| format!("d{}", c.0));
                s.push_str(&format!(
                    "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"40\" height=\"18\" rx=\"9\" fill=\"white\" stroke=\"black\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"11\" text-anchor=\"middle\">{label}</text>",
                    x - 26.0,
                    y - 9.0,
                    x - 6.0,
                    y + 4.0
                ));
            }
        }
    }
    s.push_str("</svg>\n");
    s
}

/// Place standalone SVG documents side by side in one document.
pub fn side_by_side(title: &str, parts: &[String]) -> String {
    let size = |svg: &str, attr: &str| -> f64 {
        let key = format!("{attr}=\"");
        svg.find(&key)
            .and_then(|i| svg[i + key.len()..].split('"').next())
            .and_then(|v| v.parse().ok())
            .unwrap_or(0.0)
    };
    let mut x = 0.0;
    let mut height: f64 = 0.0;
    let mut body = String::new();
    for part in parts {
        let (w, h) = (size(part, "width"), size(part, "height"));
        body.push_str(&part.replacen("<svg ", &format!("<svg x=\"{x:.0}\" y=\"36\" "), 1));
        x += w + 16.0;
        height = height.max(h);
    }
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{x:.0}\" height=\"{:.0}\" viewBox=\"0 0 {x:.0} {:.0}\" font-family=\"sans-serif\"><rect width=\"100%\" height=\"100%\" fill=\"white\"/><text x=\"12\" y=\"24\" font-size=\"18\">{}</text>{body}</svg>\n",
        height + 36.0,
        height + 36.0,
        escape(title)
    )
}

/// Okabe and Ito's colour-blind-safe palette, and one marker shape per series, so that
/// the figure reads in grey too.
pub const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 0, 0),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 158, 115),
    RGBColor(213, 94, 0),
    RGBColor(0, 114, 178),
    RGBColor(204, 121, 167),
];

/// Series `k`'s marker at `at`: seven shapes, filled or hollow, told apart in grey.
pub fn marker<DB: DrawingBackend>(
    k: usize,
    at: (i32, i32),
    color: RGBColor,
) -> DynElement<'static, DB, (i32, i32)> {
    let (filled, hollow) = (color.filled(), color.stroke_width(2));
    let square =
        |style: ShapeStyle| Rectangle::new([(at.0 - 4, at.1 - 4), (at.0 + 4, at.1 + 4)], style);
    match k % 7 {
        0 => Circle::new(at, 5, filled).into_dyn(),
        1 => TriangleMarker::new(at, 6, filled).into_dyn(),
        2 => Cross::new(at, 5, hollow).into_dyn(),
        3 => square(filled).into_dyn(),
        4 => Circle::new(at, 5, hollow).into_dyn(),
        5 => TriangleMarker::new(at, 6, hollow).into_dyn(),
        _ => square(hollow).into_dyn(),
    }
}
