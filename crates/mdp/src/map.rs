//! Grid maps: cells, positions, the TOML map format, validation and the built-in maps.
//!
//! # The map file format
//!
//! ```toml
//! name = "tiny"
//! description = "optional free text"
//! layout = '''
//! ..G
//! .#.
//! '''
//! ```
//!
//! `layout` lists the interior rows from top to bottom: `#` an obstacle, `.` an empty cell,
//! `G` the goal. The boundary of obstacles around the interior is implicit and never drawn.
//! Leading and trailing blank lines of the layout are ignored, and so is whitespace around
//! each row, so a layout may be indented. Unknown keys are refused.
//!
//! A valid map has rows of equal width, exactly one goal, at least one empty cell, every
//! free cell reachable from the goal, and at most [`MAX_SIDE`] cells a side. Files larger
//! than [`MAX_FILE_BYTES`] are refused before they are read, and a layout's size is checked
//! before any grid is allocated for it.
//!
//! Row 0 is the top line of the layout and column 0 its leftmost character, everywhere.

use std::collections::VecDeque;
use std::fmt;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{MapError, Position};

/// The largest width or height a map may have, in cells.
pub const MAX_SIDE: usize = 256;

/// The largest map file accepted, in bytes (a full `MAX_SIDE` square layout is about 66 kB).
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// The condition of a cell: what a sensor reads there.
///
/// ```
/// use mdp::Cell;
/// assert_eq!(Cell::from_char('#'), Some(Cell::Obstacle));
/// assert_eq!(Cell::Goal.to_char(), 'G');
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Cell {
    /// A free cell the robot may stand on.
    Empty,
    /// A wall; the boundary and everything beyond it read as obstacles too.
    Obstacle,
    /// The goal (the paper's cup): a free cell whose entry ends the trial.
    Goal,
}

impl Cell {
    /// The three conditions, in the order of their [`Cell::code`].
    ///
    /// ```
    /// assert_eq!(mdp::Cell::ALL.len(), 3);
    /// ```
    pub const ALL: [Cell; 3] = [Cell::Empty, Cell::Obstacle, Cell::Goal];

    /// Parse a layout character.
    ///
    /// ```
    /// assert_eq!(mdp::Cell::from_char('.'), Some(mdp::Cell::Empty));
    /// assert_eq!(mdp::Cell::from_char('x'), None);
    /// ```
    pub fn from_char(c: char) -> Option<Cell> {
        match c {
            '.' => Some(Cell::Empty),
            '#' => Some(Cell::Obstacle),
            'G' => Some(Cell::Goal),
            _ => None,
        }
    }

    /// The layout character of the cell.
    ///
    /// ```
    /// assert_eq!(mdp::Cell::Empty.to_char(), '.');
    /// ```
    pub fn to_char(self) -> char {
        match self {
            Cell::Empty => '.',
            Cell::Obstacle => '#',
            Cell::Goal => 'G',
        }
    }

    /// A small dense code (0 empty, 1 obstacle, 2 goal), used as a feature value.
    ///
    /// ```
    /// use mdp::Cell;
    /// for c in Cell::ALL { assert_eq!(Cell::from_code(c.code()), Some(c)); }
    /// ```
    pub fn code(self) -> u32 {
        self as u32
    }

    /// The cell of a [`Cell::code`].
    ///
    /// ```
    /// assert_eq!(mdp::Cell::from_code(1), Some(mdp::Cell::Obstacle));
    /// assert_eq!(mdp::Cell::from_code(9), None);
    /// ```
    pub fn from_code(code: u32) -> Option<Cell> {
        Cell::ALL.get(code as usize).copied()
    }

    /// Whether the robot may stand on the cell.
    ///
    /// ```
    /// assert!(mdp::Cell::Goal.is_free());
    /// assert!(!mdp::Cell::Obstacle.is_free());
    /// ```
    pub fn is_free(self) -> bool {
        self != Cell::Obstacle
    }

    /// A lowercase name: `empty`, `obstacle` or `goal`.
    ///
    /// ```
    /// assert_eq!(mdp::Cell::Goal.name(), "goal");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Cell::Empty => "empty",
            Cell::Obstacle => "obstacle",
            Cell::Goal => "goal",
        }
    }
}

impl fmt::Display for Cell {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A cell position in the interior: row 0 is the top row, column 0 the leftmost.
///
/// ```
/// use mdp::Pos;
/// let p = Pos::new(2, 5);
/// assert_eq!((p.row, p.col), (2, 5));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Pos {
    /// Row, from the top.
    pub row: usize,
    /// Column, from the left.
    pub col: usize,
}

impl Pos {
    /// A position from its row and column.
    ///
    /// ```
    /// assert_eq!(mdp::Pos::new(0, 1).col, 1);
    /// ```
    pub const fn new(row: usize, col: usize) -> Pos {
        Pos { row, col }
    }
}

impl fmt::Display for Pos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "(row {}, col {})", self.row, self.col)
    }
}

/// A validated grid map: the interior cells of a world whose boundary is implicit.
///
/// ```
/// use mdp::{Cell, Map, Pos};
/// let map = Map::from_layout("tiny", "..G\n.#.").unwrap();
/// assert_eq!((map.width(), map.height()), (3, 2));
/// assert_eq!(map.goal(), Pos::new(0, 2));
/// assert_eq!(map.cell(Pos::new(1, 1)), Cell::Obstacle);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Map {
    name: String,
    description: Option<String>,
    width: usize,
    height: usize,
    cells: Vec<Cell>,
    goal: Pos,
}

/// The raw shape of a map file, before validation.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MapFile {
    name: String,
    description: Option<String>,
    layout: toml::Spanned<String>,
}

impl Map {
    /// Read and validate a map file.
    ///
    /// Errors name the file and, where there is one, the line and column.
    ///
    /// ```
    /// let dir = std::env::temp_dir().join("mdp-doc-map-load");
    /// std::fs::create_dir_all(&dir).unwrap();
    /// let path = dir.join("m.toml");
    /// std::fs::write(&path, "name = \"m\"\nlayout = '''\n.G\n'''\n").unwrap();
    /// let map = mdp::Map::load(&path).unwrap();
    /// assert_eq!(map.name(), "m");
    /// ```
    pub fn load(path: &Path) -> Result<Map, MapError> {
        let source = path.display().to_string();
        let io = |e: std::io::Error| MapError::Io {
            source_name: source.clone(),
            error: e.to_string(),
        };
        let meta = std::fs::metadata(path).map_err(io)?;
        if meta.is_dir() {
            return Err(MapError::NotAFile {
                source_name: source,
            });
        }
        if meta.len() > MAX_FILE_BYTES {
            return Err(MapError::FileTooLarge {
                source_name: source,
                bytes: meta.len(),
                max: MAX_FILE_BYTES,
            });
        }
        let bytes = std::fs::read(path).map_err(io)?;
        Map::from_toml_bytes(&bytes, &source)
    }

    /// Parse and validate a map from the bytes of a TOML file; `source_name` names it in errors.
    ///
    /// ```
    /// let err = mdp::Map::from_toml_bytes(b"\xff\xfe", "bad.toml").unwrap_err();
    /// assert!(err.to_string().contains("bad.toml"));
    /// ```
    pub fn from_toml_bytes(bytes: &[u8], source_name: &str) -> Result<Map, MapError> {
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(MapError::FileTooLarge {
                source_name: source_name.to_string(),
                bytes: bytes.len() as u64,
                max: MAX_FILE_BYTES,
            });
        }
        let text = std::str::from_utf8(bytes).map_err(|e| {
            let (line, column) = line_col(bytes, e.valid_up_to());
            MapError::NotUtf8 {
                source_name: source_name.to_string(),
                at: Position { line, column },
            }
        })?;
        Map::from_toml_str(text, source_name)
    }

    /// Parse and validate a map from TOML text; `source_name` names it in errors.
    ///
    /// ```
    /// let text = "name = \"demo\"\nlayout = '''\nG..\n'''\n";
    /// let map = mdp::Map::from_toml_str(text, "demo.toml").unwrap();
    /// assert_eq!(map.width(), 3);
    /// let err = mdp::Map::from_toml_str("name = \"x\"\ncolour = 1\nlayout = 'G.'", "x.toml").unwrap_err();
    /// assert!(err.to_string().contains("colour"));
    /// ```
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Map, MapError> {
        let file: MapFile = toml::from_str(text).map_err(|e| {
            let at = e.span().map(|s| {
                let (line, column) = line_col(text.as_bytes(), s.start);
                Position { line, column }
            });
            MapError::Toml {
                source_name: source_name.to_string(),
                at,
                message: e.message().trim().to_string(),
            }
        })?;
        if file.name.trim().is_empty() {
            return Err(MapError::EmptyName {
                source_name: source_name.to_string(),
            });
        }
        let span = file.layout.span();
        let origin = layout_origin(text, span.start, span.end, file.layout.get_ref());
        Map::build(
            file.name,
            file.description,
            file.layout.get_ref(),
            source_name,
            origin,
        )
    }

    /// Build a map from a bare layout (rows separated by newlines), for code and tests.
    ///
    /// Errors report positions as layout rows and columns (1-based).
    ///
    /// ```
    /// let map = mdp::Map::from_layout("strip", ".G.").unwrap();
    /// assert_eq!(map.states(), 2);
    /// assert!(mdp::Map::from_layout("none", "...").is_err());
    /// ```
    pub fn from_layout(name: &str, layout: &str) -> Result<Map, MapError> {
        Map::build(
            name.to_string(),
            None,
            layout,
            name,
            LayoutOrigin::LayoutRelative,
        )
    }

    fn build(
        name: String,
        description: Option<String>,
        layout: &str,
        source_name: &str,
        origin: LayoutOrigin,
    ) -> Result<Map, MapError> {
        let src = || source_name.to_string();
        // Rows with their index among the layout's lines (for positions), blank edges dropped.
        let lines: Vec<(usize, &str)> = layout.split('\n').enumerate().collect();
        let first = lines.iter().position(|(_, l)| !l.trim().is_empty());
        let last = lines.iter().rposition(|(_, l)| !l.trim().is_empty());
        let (first, last) = match (first, last) {
            (Some(f), Some(l)) => (f, l),
            _ => return Err(MapError::EmptyLayout { source_name: src() }),
        };
        let rows = &lines[first..=last];
        // Size checks come before any per-cell allocation.
        let height = rows.len();
        let trimmed = |l: &str| l.trim_end_matches('\r').trim().chars().count();
        let width = trimmed(rows[0].1);
        let widest = rows.iter().map(|(_, l)| trimmed(l)).max().unwrap_or(0);
        if height > MAX_SIDE || widest > MAX_SIDE {
            return Err(MapError::TooLarge {
                source_name: src(),
                width: widest,
                height,
                max: MAX_SIDE,
            });
        }
        let pos_of = |line_idx: usize, raw: &str, char_idx: usize| -> Position {
            let lead = raw.chars().take_while(|c| c.is_whitespace()).count();
            origin.position(line_idx, lead + char_idx)
        };
        let mut cells = Vec::with_capacity(width * height);
        let mut goal: Option<(Pos, Position)> = None;
        for (r, &(line_idx, raw)) in rows.iter().enumerate() {
            let row = raw.trim_end_matches('\r').trim();
            let n = row.chars().count();
            if n != width {
                return Err(MapError::RaggedRow {
                    source_name: src(),
                    at: pos_of(line_idx, raw, n.min(width)),
                    row: r,
                    expected: width,
                    found: n,
                });
            }
            for (c, ch) in row.chars().enumerate() {
                let at = pos_of(line_idx, raw, c);
                let cell = Cell::from_char(ch).ok_or_else(|| MapError::UnknownChar {
                    source_name: src(),
                    at,
                    found: ch,
                })?;
                if cell == Cell::Goal {
                    if let Some((_, first_at)) = goal {
                        return Err(MapError::SecondGoal {
                            source_name: src(),
                            at,
                            first: first_at,
                        });
                    }
                    goal = Some((Pos::new(r, c), at));
                }
                cells.push(cell);
            }
        }
        let (goal, _) = goal.ok_or(MapError::NoGoal { source_name: src() })?;
        if !cells.contains(&Cell::Empty) {
            return Err(MapError::NoStates { source_name: src() });
        }
        let map = Map {
            name,
            description,
            width,
            height,
            cells,
            goal,
        };
        if let Some(p) = map.first_unreachable() {
            let (line_idx, raw) = rows[p.row];
            return Err(MapError::Unreachable {
                source_name: src(),
                at: pos_of(line_idx, raw, p.col),
                cell: p,
            });
        }
        Ok(map)
    }

    /// The first free cell (row-major) from which the goal cannot be reached.
    fn first_unreachable(&self) -> Option<Pos> {
        let mut seen = vec![false; self.cells.len()];
        let mut queue = VecDeque::from([self.goal]);
        seen[self.index(self.goal)] = true;
        while let Some(p) = queue.pop_front() {
            for q in self.neighbours(p) {
                let i = self.index(q);
                if !seen[i] && self.cells[i].is_free() {
                    seen[i] = true;
                    queue.push_back(q);
                }
            }
        }
        (0..self.cells.len())
            .find(|&i| self.cells[i].is_free() && !seen[i])
            .map(|i| Pos::new(i / self.width, i % self.width))
    }

    /// The in-grid 4-neighbours of a position.
    fn neighbours(&self, p: Pos) -> impl Iterator<Item = Pos> + '_ {
        let (r, c) = (p.row as isize, p.col as isize);
        [(r - 1, c), (r + 1, c), (r, c - 1), (r, c + 1)]
            .into_iter()
            .filter(|&(r, c)| {
                r >= 0 && c >= 0 && (r as usize) < self.height && (c as usize) < self.width
            })
            .map(|(r, c)| Pos::new(r as usize, c as usize))
    }

    fn index(&self, p: Pos) -> usize {
        p.row * self.width + p.col
    }

    /// The map's name.
    ///
    /// ```
    /// assert_eq!(mdp::builtin("tan8x8").unwrap().name(), "tan8x8");
    /// ```
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The map's description, if it has one.
    ///
    /// ```
    /// assert!(mdp::builtin("tan8x8").unwrap().description().is_some());
    /// ```
    pub fn description(&self) -> Option<&str> {
        self.description.as_deref()
    }

    /// Interior width in cells.
    ///
    /// ```
    /// assert_eq!(mdp::builtin("tan8x8").unwrap().width(), 8);
    /// ```
    pub fn width(&self) -> usize {
        self.width
    }

    /// Interior height in cells.
    ///
    /// ```
    /// assert_eq!(mdp::builtin("tan3x3").unwrap().height(), 3);
    /// ```
    pub fn height(&self) -> usize {
        self.height
    }

    /// The goal's position.
    ///
    /// ```
    /// assert_eq!(mdp::builtin("tan3x3").unwrap().goal(), mdp::Pos::new(0, 2));
    /// ```
    pub fn goal(&self) -> Pos {
        self.goal
    }

    /// The cell at an interior position.
    ///
    /// # Panics
    /// If `p` is outside the interior; use [`Map::cell_at`] for any offset.
    ///
    /// ```
    /// let map = mdp::builtin("tan3x3").unwrap();
    /// assert_eq!(map.cell(mdp::Pos::new(0, 2)), mdp::Cell::Goal);
    /// ```
    pub fn cell(&self, p: Pos) -> Cell {
        assert!(
            p.row < self.height && p.col < self.width,
            "{p} is outside the map"
        );
        self.cells[self.index(p)]
    }

    /// The cell at a signed row and column: anything outside the interior (the boundary
    /// and beyond) reads as [`Cell::Obstacle`].
    ///
    /// ```
    /// let map = mdp::builtin("tan3x3").unwrap();
    /// assert_eq!(map.cell_at(-1, 0), mdp::Cell::Obstacle);
    /// assert_eq!(map.cell_at(0, 2), mdp::Cell::Goal);
    /// ```
    pub fn cell_at(&self, row: i64, col: i64) -> Cell {
        if row < 0 || col < 0 || row >= self.height as i64 || col >= self.width as i64 {
            Cell::Obstacle
        } else {
            self.cells[row as usize * self.width + col as usize]
        }
    }

    /// Every interior cell in row-major order with its position.
    ///
    /// ```
    /// let n = mdp::builtin("tan8x8").unwrap().cells().filter(|(_, c)| c.is_free()).count();
    /// assert_eq!(n, 51);
    /// ```
    pub fn cells(&self) -> impl Iterator<Item = (Pos, Cell)> + '_ {
        self.cells
            .iter()
            .enumerate()
            .map(|(i, &c)| (Pos::new(i / self.width, i % self.width), c))
    }

    /// The number of states: free cells other than the goal.
    ///
    /// ```
    /// assert_eq!(mdp::builtin("tan8x8").unwrap().states(), 50);
    /// ```
    pub fn states(&self) -> usize {
        self.cells.iter().filter(|&&c| c == Cell::Empty).count()
    }

    /// The number of interior obstacles.
    ///
    /// ```
    /// assert_eq!(mdp::builtin("tan8x8").unwrap().obstacles(), 13);
    /// ```
    pub fn obstacles(&self) -> usize {
        self.cells.iter().filter(|&&c| c == Cell::Obstacle).count()
    }

    /// The layout as text, one row per line, as in a map file.
    ///
    /// ```
    /// let map = mdp::Map::from_layout("t", ".G\n#.").unwrap();
    /// assert_eq!(map.layout(), ".G\n#.\n");
    /// ```
    pub fn layout(&self) -> String {
        let mut s = String::with_capacity((self.width + 1) * self.height);
        for row in self.cells.chunks(self.width) {
            s.extend(row.iter().map(|c| c.to_char()));
            s.push('\n');
        }
        s
    }

    /// The map as a TOML map file that [`Map::from_toml_str`] reads back.
    ///
    /// ```
    /// let map = mdp::builtin("tan3x3").unwrap();
    /// let back = mdp::Map::from_toml_str(&map.to_toml(), "copy").unwrap();
    /// assert_eq!(back, map);
    /// ```
    pub fn to_toml(&self) -> String {
        let mut s = format!("name = {}\n", toml_string(&self.name));
        if let Some(d) = &self.description {
            s.push_str(&format!("description = {}\n", toml_string(d)));
        }
        s.push_str("layout = '''\n");
        s.push_str(&self.layout());
        s.push_str("'''\n");
        s
    }

    /// Build from validated parts (for the random generator, which guarantees validity).
    pub(crate) fn from_parts(
        name: String,
        description: Option<String>,
        width: usize,
        cells: Vec<Cell>,
    ) -> Map {
        let layout: String = cells
            .chunks(width)
            .map(|r| r.iter().map(|c| c.to_char()).collect::<String>())
            .collect::<Vec<_>>()
            .join("\n");
        let mut map = Map::from_layout(&name, &layout).expect("generator produced an invalid map");
        map.description = description;
        map
    }
}

fn toml_string(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// How positions inside the layout string map to positions in the file.
#[derive(Clone, Copy)]
enum LayoutOrigin {
    /// The layout's characters appear verbatim in the file from this line and column
    /// (1-based) onwards: line 0 of the layout starts at `column`, later ones at column 1.
    File { line: usize, column: usize },
    /// Escapes or a bare layout: report layout rows and columns.
    LayoutRelative,
}

impl LayoutOrigin {
    fn position(self, line_idx: usize, char_idx: usize) -> Position {
        match self {
            LayoutOrigin::File { line, column } if line_idx == 0 => Position {
                line,
                column: column + char_idx,
            },
            LayoutOrigin::File { line, .. } => Position {
                line: line + line_idx,
                column: 1 + char_idx,
            },
            LayoutOrigin::LayoutRelative => Position {
                line: line_idx + 1,
                column: char_idx + 1,
            },
        }
    }
}

/// Find where the layout's content starts in the file, when it appears there verbatim.
fn layout_origin(text: &str, start: usize, end: usize, value: &str) -> LayoutOrigin {
    let Some(raw) = text.get(start..end) else {
        return LayoutOrigin::LayoutRelative;
    };
    let (open, verbatim) = if raw.starts_with("'''") {
        (3, true)
    } else if raw.starts_with("\"\"\"") {
        (3, !raw.contains('\\'))
    } else if raw.starts_with('\'') {
        (1, true)
    } else {
        (1, !raw.contains('\\'))
    };
    if !verbatim {
        return LayoutOrigin::LayoutRelative;
    }
    let mut content = start + open;
    // TOML drops a newline that immediately follows the opening delimiter.
    if open == 3 {
        if text[content..].starts_with("\r\n") {
            content += 2;
        } else if text[content..].starts_with('\n') {
            content += 1;
        }
    }
    if !text[content..].starts_with(value) {
        return LayoutOrigin::LayoutRelative;
    }
    let (line, column) = line_col(text.as_bytes(), content);
    LayoutOrigin::File { line, column }
}

/// 1-based line and column (in characters) of a byte offset.
fn line_col(bytes: &[u8], offset: usize) -> (usize, usize) {
    let before = &bytes[..offset.min(bytes.len())];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let column = String::from_utf8_lossy(&before[line_start..])
        .chars()
        .count()
        + 1;
    (line, column)
}

/// The built-in maps, compiled into the crate: `(name, TOML text)`.
const BUILTINS: &[(&str, &str)] = &[
    ("tan3x3", include_str!("../maps/tan3x3.toml")),
    ("tan8x8", include_str!("../maps/tan8x8.toml")),
    ("tan8x8-maze", include_str!("../maps/tan8x8-maze.toml")),
    ("dyna9x6", include_str!("../maps/dyna9x6.toml")),
    ("open8x8", include_str!("../maps/open8x8.toml")),
    ("corridors9x5", include_str!("../maps/corridors9x5.toml")),
];

/// The names of the built-in maps, in a fixed order.
///
/// ```
/// assert!(mdp::builtin_names().contains(&"tan8x8"));
/// ```
pub fn builtin_names() -> Vec<&'static str> {
    BUILTINS.iter().map(|(n, _)| *n).collect()
}

/// A built-in map by name, or `None` if there is no such map.
///
/// ```
/// let map = mdp::builtin("tan8x8").unwrap();
/// assert_eq!((map.width(), map.height(), map.states()), (8, 8, 50));
/// assert!(mdp::builtin("nope").is_none());
/// ```
pub fn builtin(name: &str) -> Option<Map> {
    BUILTINS.iter().find(|(n, _)| *n == name).map(|(n, text)| {
        Map::from_toml_str(text, &format!("built-in map {n}")).expect("built-in maps are valid")
    })
}

/// A map from a spec:
///
/// | spec | map |
/// |---|---|
/// | `tan8x8` | a built-in map |
/// | `path/to/map.toml` | a map file |
/// | `random:WxH:DENSITY:SEED` | a [`RandomMap`](crate::RandomMap) drawn with `Xoshiro256PlusPlus` seeded by SEED |
/// | `SPEC@ROW:COL` | the map of SPEC with its goal moved to (ROW, COL), which must be free |
///
/// A built-in name or an existing file wins over the other readings.
///
/// ```
/// assert_eq!(mdp::resolve("tan3x3").unwrap().states(), 8);
/// assert_eq!(mdp::resolve("tan3x3@2:0").unwrap().goal(), mdp::Pos::new(2, 0));
/// let r = mdp::resolve("random:7x5:0.2:3").unwrap();
/// assert_eq!((r.width(), r.height()), (7, 5));
/// let err = mdp::resolve("no-such-map.toml").unwrap_err();
/// assert!(err.to_string().contains("no-such-map.toml"));
/// ```
pub fn resolve(spec: &str) -> Result<Map, MapError> {
    if let Some(map) = builtin(spec) {
        return Ok(map);
    }
    let path = Path::new(spec);
    if path.exists() {
        return Map::load(path);
    }
    let bad = |reason: &str| MapError::BadSpec {
        spec: spec.to_string(),
        reason: reason.to_string(),
    };
    if let Some(rest) = spec.strip_prefix("random:") {
        let parts: Vec<&str> = rest.split(':').collect();
        let [size, density, seed] = parts[..] else {
            return Err(bad("expected random:WxH:DENSITY:SEED"));
        };
        let (w, h) = size
            .split_once('x')
            .ok_or_else(|| bad("the size is not WxH"))?;
        let params = crate::RandomMap {
            width: w.parse().map_err(|_| bad("the width is not a number"))?,
            height: h.parse().map_err(|_| bad("the height is not a number"))?,
            obstacle_density: density
                .parse()
                .map_err(|_| bad("the density is not a number"))?,
        };
        let seed: u64 = seed.parse().map_err(|_| bad("the seed is not a number"))?;
        let mut rng = <rand_xoshiro::Xoshiro256PlusPlus as rand::SeedableRng>::seed_from_u64(seed);
        return params.generate(spec, &mut rng);
    }
    if let Some((base, goal)) = spec.rsplit_once('@') {
        let (r, c) = goal
            .split_once(':')
            .ok_or_else(|| bad("expected SPEC@ROW:COL"))?;
        let to = Pos::new(
            r.parse().map_err(|_| bad("the row is not a number"))?,
            c.parse().map_err(|_| bad("the column is not a number"))?,
        );
        return resolve(base)?.with_goal(to, spec);
    }
    Err(MapError::UnknownMap {
        name: spec.to_string(),
        builtins: builtin_names().join(", "),
    })
}

impl Map {
    /// The same map with its goal moved to `to` (a free cell), under a new name.
    ///
    /// ```
    /// let map = mdp::builtin("tan3x3").unwrap().with_goal(mdp::Pos::new(2, 2), "moved").unwrap();
    /// assert_eq!((map.goal(), map.name()), (mdp::Pos::new(2, 2), "moved"));
    /// assert!(mdp::builtin("tan8x8-maze").unwrap().with_goal(mdp::Pos::new(0, 5), "x").is_err());
    /// ```
    pub fn with_goal(&self, to: Pos, name: &str) -> Result<Map, MapError> {
        if to.row >= self.height || to.col >= self.width || !self.cell(to).is_free() {
            return Err(MapError::BadSpec {
                spec: name.to_string(),
                reason: format!("{to} is not a free cell of {}", self.name),
            });
        }
        let mut cells = self.cells.clone();
        cells[self.index(self.goal)] = Cell::Empty;
        cells[self.index(to)] = Cell::Goal;
        let description = format!("The map {} with its goal moved to {to}.", self.name);
        Ok(Map::from_parts(
            name.to_string(),
            Some(description),
            self.width,
            cells,
        ))
    }
}
