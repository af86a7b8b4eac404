//! The validated map: its cells, its goal, and the checks that make a layout a map.
//!
//! A valid map has rows of equal width, exactly one goal, at least one empty cell, every
//! free cell reachable from the goal, and at most [`MAX_SIDE`] cells a side. A layout's
//! size is checked before any grid is allocated for it. Reading maps from files is in the
//! file-format module ([`Map::load`]), the built-in maps in [`builtin`](crate::builtin),
//! and map specs such as `random:WxH:D:S` or `MAP@ROW:COL` in [`resolve`](crate::resolve).
//!
//! Row 0 is the top line of the layout and column 0 its leftmost character, everywhere.

use std::collections::VecDeque;

use crate::error::{MapError, Position};
use crate::geometry::{Cell, Pos};

/// The largest width or height a map may have, in cells.
pub const MAX_SIDE: usize = 256;

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

impl Map {
    /// Build a map from a bare layout (rows separated by newlines), for code and tests.
    ///
    /// Errors report positions as layout rows and columns (1-based).
    ///
    /// ```
    /// let map = mdp::Map::from_layout("strip", ".G.").unwrap();
    /// assert_eq!(map.states().len(), 2);
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

    pub(crate) fn build(
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

    /// The states: the free cells other than the goal, in row-major order. These are the
    /// cells where trials start, and the same cells, in the same order, as
    /// [`GridWorld::states`](crate::GridWorld::states) (which gives their state ids; the
    /// MDP's [`num_states`](crate::Mdp::num_states) also counts the goal).
    ///
    /// ```
    /// let map = mdp::builtin("tan8x8").unwrap();
    /// assert_eq!(map.states().len(), 50);
    /// let world = mdp::GridWorld::new(&map);
    /// let ids: Vec<_> = map.states().iter().map(|&p| world.state_at(p).unwrap()).collect();
    /// assert_eq!(ids, world.states());
    /// ```
    pub fn states(&self) -> Vec<Pos> {
        self.cells()
            .filter(|&(_, c)| c == Cell::Empty)
            .map(|(p, _)| p)
            .collect()
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
        #[cfg_attr(
            not(test),
            expect(
                clippy::expect_used,
                reason = "callers (the random generator, goal moves) build valid cells; a failure is a bug of the crate"
            )
        )]
        let mut map = Map::from_layout(&name, &layout).expect("generator produced an invalid map");
        map.description = description;
        map
    }
}

/// How positions inside the layout string map to positions in the file.
#[derive(Clone, Copy)]
pub(crate) enum LayoutOrigin {
    /// The layout's characters appear verbatim in the file from this line and column
    /// (1-based) onwards: line 0 of the layout starts at `column`, later ones at column 1.
    File { line: usize, column: usize },
    /// Escapes or a bare layout: report layout rows and columns.
    LayoutRelative,
}

impl LayoutOrigin {
    pub(crate) fn position(self, line_idx: usize, char_idx: usize) -> Position {
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
