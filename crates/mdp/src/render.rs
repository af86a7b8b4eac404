//! Drawing maps as text and as SVG, with optional overlays (arrows, labels, tooltips)
//! that later stages use to show policies and state descriptions.
//!
//! The SVG is written by hand: it needs no fonts at generation time and opens in any
//! browser.

use std::fmt::Write as _;

use crate::geometry::{Cell, Pos};
use crate::grid::Action;
use crate::map::Map;

/// What to draw on top of a map.
///
/// ```
/// use mdp::{Action, Overlay, Pos};
/// let mut o = Overlay::default();
/// o.arrow(Pos::new(0, 0), Action::Right).label(Pos::new(0, 0), "d1");
/// assert_eq!(o.arrows.len(), 1);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overlay {
    /// A title above the SVG drawing.
    pub title: Option<String>,
    /// Arrows drawn from the centre of a cell; several per cell are allowed.
    pub arrows: Vec<(Pos, Action)>,
    /// Short text drawn in a cell.
    pub labels: Vec<(Pos, String)>,
    /// Text shown when hovering a cell (SVG only).
    pub tooltips: Vec<(Pos, String)>,
    /// Cells to shade (SVG only), with a CSS colour.
    pub shades: Vec<(Pos, String)>,
    /// Lines of a legend drawn below the grid (SVG only).
    pub legend: Vec<String>,
}

impl Overlay {
    /// Add an arrow.
    ///
    /// ```
    /// let mut o = mdp::Overlay::default();
    /// o.arrow(mdp::Pos::new(1, 1), mdp::Action::Up);
    /// ```
    pub fn arrow(&mut self, p: Pos, a: Action) -> &mut Self {
        self.arrows.push((p, a));
        self
    }

    /// Add a label.
    ///
    /// ```
    /// let mut o = mdp::Overlay::default();
    /// o.label(mdp::Pos::new(1, 1), "7");
    /// ```
    pub fn label(&mut self, p: Pos, text: impl Into<String>) -> &mut Self {
        self.labels.push((p, text.into()));
        self
    }

    /// Add a tooltip.
    ///
    /// ```
    /// let mut o = mdp::Overlay::default();
    /// o.tooltip(mdp::Pos::new(1, 1), "features: up=empty");
    /// ```
    pub fn tooltip(&mut self, p: Pos, text: impl Into<String>) -> &mut Self {
        self.tooltips.push((p, text.into()));
        self
    }
}

/// The map as text with its boundary drawn: `#` obstacles, `.` empty, `G` goal; a cell
/// with one arrow shows it (`^ v < >`), a cell with several shows `+`.
///
/// ```
/// use mdp::{Action, Overlay, Pos};
/// let map = mdp::builtin("tan3x3").unwrap();
/// let mut o = Overlay::default();
/// o.arrow(Pos::new(0, 1), Action::Right);
/// let text = mdp::render_text(&map, &o);
/// assert_eq!(text.lines().nth(1).unwrap(), "#.>G#");
/// ```
pub fn render_text(map: &Map, overlay: &Overlay) -> String {
    let w = map.width();
    let mut grid: Vec<Vec<char>> = (0..map.height())
        .map(|r| (0..w).map(|c| map.cell(Pos::new(r, c)).to_char()).collect())
        .collect();
    let mut count = vec![0usize; w * map.height()];
    for &(p, a) in &overlay.arrows {
        if p.row < map.height() && p.col < w {
            count[p.row * w + p.col] += 1;
            grid[p.row][p.col] = if count[p.row * w + p.col] > 1 {
                '+'
            } else {
                a.arrow()
            };
        }
    }
    let border: String = "#".repeat(w + 2);
    let mut s = String::with_capacity((w + 3) * (map.height() + 2));
    s.push_str(&border);
    s.push('\n');
    for row in grid {
        s.push('#');
        s.extend(row);
        s.push_str("#\n");
    }
    s.push_str(&border);
    s.push('\n');
    s
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The map as a standalone SVG document, boundary included, with the overlay on top.
///
/// ```
/// let map = mdp::builtin("tan8x8").unwrap();
/// let svg = mdp::render_svg(&map, &mdp::Overlay::default());
/// assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
/// ```
pub fn render_svg(map: &Map, overlay: &Overlay) -> String {
    const CELL: usize = 48;
    const LINE: usize = 16;
    let (w, h) = (map.width() + 2, map.height() + 2);
    let top = if overlay.title.is_some() { 28 } else { 0 };
    // Wide enough for the grid, the title and the legend (about 7 px per character).
    let text_width = |chars: usize, px: usize| chars * px / 10 + 16;
    let width = (w * CELL)
        .max(
            overlay
                .title
                .as_ref()
                .map_or(0, |t| text_width(t.chars().count(), 92)),
        )
        .max(
            overlay
                .legend
                .iter()
                .map(|l| text_width(l.chars().count(), 70))
                .max()
                .unwrap_or(0),
        );
    let height =
        top + h * CELL + overlay.legend.len() * LINE + usize::from(!overlay.legend.is_empty()) * 8;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif">"#
    );
    s.push_str(r#"<rect width="100%" height="100%" fill="white"/>"#);
    s.push('\n');
    if let Some(t) = &overlay.title {
        let _ = writeln!(
            s,
            r#"<text x="{}" y="20" font-size="16" text-anchor="middle">{}</text>"#,
            width / 2,
            escape(t)
        );
    }
    let xy = |p: Pos| ((p.col + 1) * CELL, top + (p.row + 1) * CELL);
    for r in 0..h {
        for c in 0..w {
            let cell = map.cell_at(r as i64 - 1, c as i64 - 1);
            let fill = match cell {
                Cell::Obstacle => "#555555",
                Cell::Empty => "#ffffff",
                Cell::Goal => "#ffe08a",
            };
            let _ = writeln!(
                s,
                r##"<rect x="{}" y="{}" width="{CELL}" height="{CELL}" fill="{fill}" stroke="#999999"/>"##,
                c * CELL,
                top + r * CELL
            );
        }
    }
    for (p, colour) in &overlay.shades {
        let (x, y) = xy(*p);
        let _ = writeln!(
            s,
            r#"<rect x="{x}" y="{y}" width="{CELL}" height="{CELL}" fill="{}" fill-opacity="0.35"/>"#,
            escape(colour)
        );
    }
    let (gx, gy) = xy(map.goal());
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" font-size="20" text-anchor="middle" font-weight="bold">G</text>"#,
        gx + CELL / 2,
        gy + CELL / 2 + 7
    );
    for &(p, a) in &overlay.arrows {
        let (x, y) = xy(p);
        let (cx, cy) = ((x + CELL / 2) as i64, (y + CELL / 2) as i64);
        let o = a.offset();
        let len = (CELL as i64) * 2 / 5;
        let (ex, ey) = (cx + o.dx as i64 * len, cy - o.dy as i64 * len);
        let _ = writeln!(
            s,
            r##"<line x1="{cx}" y1="{cy}" x2="{ex}" y2="{ey}" stroke="#1f5fbf" stroke-width="3" marker-end="url(#head)"/>"##
        );
    }
    for (p, text) in &overlay.labels {
        let (x, y) = xy(*p);
        let _ = writeln!(
            s,
            r##"<text x="{}" y="{}" font-size="11" fill="#333333">{}</text>"##,
            x + 3,
            y + 12,
            escape(text)
        );
    }
    for (p, text) in &overlay.tooltips {
        let (x, y) = xy(*p);
        let _ = writeln!(
            s,
            r#"<rect x="{x}" y="{y}" width="{CELL}" height="{CELL}" fill="transparent"><title>{}</title></rect>"#,
            escape(text)
        );
    }
    for (i, line) in overlay.legend.iter().enumerate() {
        let _ = writeln!(
            s,
            r#"<text x="6" y="{}" font-size="12">{}</text>"#,
            top + h * CELL + 4 + (i + 1) * LINE,
            escape(line)
        );
    }
    s.push_str(r##"<defs><marker id="head" markerWidth="6" markerHeight="6" refX="3" refY="3" orient="auto"><path d="M0,0 L6,3 L0,6 z" fill="#1f5fbf"/></marker></defs>"##);
    s.push_str("\n</svg>\n");
    s
}
