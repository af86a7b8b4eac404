//! The grid's vocabulary: what a cell holds ([`Cell`]), where a cell is ([`Pos`]), and
//! where a cell is seen from the robot ([`Offset`]).
//!
//! Everything else in the crate builds on these three values; this module depends on
//! nothing else in the crate.

use std::cmp::Ordering;
use std::fmt;

use serde::{Deserialize, Serialize};

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

/// A Cartesian offset from the robot: `dx` to the right, `dy` up.
///
/// ```
/// let o = mdp::Offset::new(-2, 1);
/// assert_eq!((o.dx, o.dy), (-2, 1));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Offset {
    /// Columns to the right (negative: left).
    pub dx: i32,
    /// Rows up (negative: down).
    pub dy: i32,
}

impl Offset {
    /// An offset from its two components.
    ///
    /// ```
    /// assert_eq!(mdp::Offset::new(1, 0).dx, 1);
    /// ```
    pub const fn new(dx: i32, dy: i32) -> Offset {
        Offset { dx, dy }
    }

    /// Compare two offsets by clockwise angle from straight up, exactly.
    ///
    /// ```
    /// use mdp::Offset;
    /// use std::cmp::Ordering;
    /// assert_eq!(Offset::new(0, 1).clockwise_cmp(&Offset::new(1, 0)), Ordering::Less);
    /// assert_eq!(Offset::new(-1, 0).clockwise_cmp(&Offset::new(0, -1)), Ordering::Greater);
    /// ```
    pub fn clockwise_cmp(&self, other: &Offset) -> Ordering {
        // Half 0 covers angles [0, pi): straight up and everything to the right.
        let half = |o: &Offset| u8::from(!(o.dx > 0 || (o.dx == 0 && o.dy > 0)));
        half(self).cmp(&half(other)).then_with(|| {
            // Within a half, b is clockwise from a when the cross product a x b is negative.
            let cross = self.dx as i64 * other.dy as i64 - self.dy as i64 * other.dx as i64;
            cross.cmp(&0)
        })
    }
}

impl fmt::Display for Offset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "({}, {})", self.dx, self.dy)
    }
}
