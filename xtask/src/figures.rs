//! Figures: learning curves (plotters, with an embedded font so no system font is
//! needed), decision trees drawn as SVG, and side-by-side composition.

use std::path::Path;
use std::sync::Once;

use anyhow::{Result, anyhow};
use cslearn::{Branch, DecisionTree, Node, NodeId};
use csql::TracePoint;
use mdp::{Cell, Feature, FeatureSpace};
use plotters::prelude::*;

fn register_font() {
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

/// A learning curve: its name and, per trial, the mean, lowest and highest value.
pub type Curve = (String, Vec<(f64, f64, f64)>);

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

/// Cumulative sensing cost against trials, one line per strategy (the mean over runs)
/// with a band from the lowest to the highest run.
pub fn learning_curves(path: &Path, title: &str, curves: &[Curve]) -> Result<()> {
    register_font();
    let plot_err = |e: &dyn std::fmt::Display| anyhow!("drawing {}: {e}", path.display());
    // Drawn into memory, then written through a temporary file and a rename.
    let mut svg = String::new();
    let root = SVGBackend::with_string(&mut svg, (960, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_err(&e))?;
    let trials = curves.iter().map(|c| c.1.len()).max().unwrap_or(1).max(2) as f64;
    let top = curves
        .iter()
        .flat_map(|c| c.1.iter().map(|p| p.2))
        .fold(1.0, f64::max);
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(90)
        .build_cartesian_2d((1.0..trials).log_scale(), 0.0..top * 1.05)
        .map_err(|e| plot_err(&e))?;
    chart
        .configure_mesh()
        .x_desc("trial (log scale)")
        .y_desc("cumulative sensing cost")
        .y_label_formatter(&|y| format!("{y:.0}"))
        .x_label_formatter(&|x| format!("{x:.0}"))
        .draw()
        .map_err(|e| plot_err(&e))?;
    for (i, (name, points)) in curves.iter().enumerate() {
        let colour = Palette99::pick(i).to_rgba();
        let x = |t: usize| (t + 1) as f64;
        let band: Vec<(f64, f64)> = points
            .iter()
            .enumerate()
            .map(|(t, p)| (x(t), p.2))
            .chain(points.iter().enumerate().rev().map(|(t, p)| (x(t), p.1)))
            .collect();
        chart
            .draw_series(std::iter::once(Polygon::new(band, colour.mix(0.15))))
            .map_err(|e| plot_err(&e))?;
        chart
            .draw_series(LineSeries::new(
                points.iter().enumerate().map(|(t, p)| (x(t), p.0)),
                colour.stroke_width(2),
            ))
            .map_err(|e| plot_err(&e))?
            .label(name.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .label_font(("sans-serif", 15))
        .draw()
        .map_err(|e| plot_err(&e))?;
    root.present().map_err(|e| plot_err(&e))?;
    drop(chart);
    drop(root);
    crate::files::write_atomic(path, svg)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A decision tree over grid descriptions as SVG: split nodes name the sensed offset
/// `(dx, dy)` and its cost, edges the cell value, leaves the description. "Other" branches
/// that lead to no description are left out.
pub fn tree_svg(tree: &DecisionTree, space: &FeatureSpace, title: &str) -> String {
    const W: f64 = 78.0;
    const H: f64 = 64.0;
    // Leaf order gives x; depth gives y.
    fn drawn(tree: &DecisionTree, id: NodeId) -> bool {
        !matches!(tree.node(id), Node::Leaf { class: None, .. })
    }
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
        let x = if kids.is_empty() {
            *next += 1.0;
            *next - 1.0
        } else {
            let xs: Vec<f64> = kids
                .iter()
                .map(|&k| layout(tree, k, depth + 1, next, pos))
                .collect();
            (xs[0] + xs[xs.len() - 1]) / 2.0
        };
        pos.push((id, x, depth));
        x
    }
    let mut pos = Vec::new();
    let mut next = 0.0;
    layout(tree, tree.root(), 0, &mut next, &mut pos);
    pos.sort_by_key(|p| p.0);
    let at = |id: NodeId| {
        let p = pos.iter().find(|p| p.0 == id).expect("laid out");
        (20.0 + W / 2.0 + p.1 * W, 50.0 + p.2 as f64 * H)
    };
    let depth = pos.iter().map(|p| p.2).max().unwrap_or(0);
    let width = 40.0 + next.max(1.0) * W;
    let height = 90.0 + depth as f64 * H;
    let mut s = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif">"#
    );
    s.push_str(r#"<rect width="100%" height="100%" fill="white"/>"#);
    s.push_str(&format!(
        r#"<text x="{:.0}" y="22" font-size="15" text-anchor="middle">{}</text>"#,
        width / 2.0,
        escape(title)
    ));
    for &(id, _, _) in &pos {
        let (x, y) = at(id);
        for (branch, child) in tree.node(id).children() {
            if !drawn(tree, child) {
                continue;
            }
            let (cx, cy) = at(child);
            let label = match branch {
                Branch::Value(v) => Cell::from_code(v.0).map_or("?", |c| c.name()).to_string(),
                Branch::Missing => "missing".to_string(),
                Branch::Other => "other".to_string(),
            };
            s.push_str(&format!(
                "<line x1=\"{x:.1}\" y1=\"{:.1}\" x2=\"{cx:.1}\" y2=\"{:.1}\" stroke=\"#888\"/>",
                y + 12.0,
                cy - 12.0
            ));
            s.push_str(&format!(
                "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"10\" fill=\"#555\" text-anchor=\"middle\">{label}</text>",
                x + (cx - x) * 0.62,
                y + (cy - y) * 0.62 + 3.0
            ));
        }
    }
    for &(id, _, _) in &pos {
        let (x, y) = at(id);
        match tree.node(id) {
            Node::Split { feature, cost, .. } => {
                let o = space.offset(Feature(feature.0));
                s.push_str(&format!(
                    "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"68\" height=\"24\" rx=\"4\" fill=\"#e8f0fb\" stroke=\"#1f5fbf\"/><text x=\"{x:.1}\" y=\"{:.1}\" font-size=\"11\" text-anchor=\"middle\">({}, {}) c={}</text>",
                    x - 34.0,
                    y - 12.0,
                    y + 4.0,
                    o.dx,
                    o.dy,
                    cost.get()
                ));
            }
            Node::Leaf { class, .. } => {
                let label = class.map_or("none".to_string(), |c| format!("d{}", c.0));
                s.push_str(&format!(
                    "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"40\" height=\"22\" rx=\"11\" fill=\"#fff4d6\" stroke=\"#b58900\"/><text x=\"{x:.1}\" y=\"{:.1}\" font-size=\"11\" text-anchor=\"middle\">{label}</text>",
                    x - 20.0,
                    y - 11.0,
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
