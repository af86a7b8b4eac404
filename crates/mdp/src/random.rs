//! A seeded generator of random valid maps.

use std::collections::VecDeque;

use rand::seq::SliceRandom;
use rand::{Rng, RngExt};
use serde::{Deserialize, Serialize};

use crate::error::MapError;
use crate::geometry::Cell;
use crate::map::{MAX_SIDE, Map};

/// Parameters of a random map.
///
/// ```
/// let p = mdp::RandomMap { width: 8, height: 8, obstacle_density: 0.2 };
/// assert!(p.validate().is_ok());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RandomMap {
    /// Interior width, 1 to [`MAX_SIDE`].
    pub width: usize,
    /// Interior height, 1 to [`MAX_SIDE`]; width times height must be at least 2.
    pub height: usize,
    /// The share of cells drawn as obstacles, in `[0, 1)`. Free cells that end up cut off
    /// from the goal are then filled in, so the final share can be somewhat higher.
    pub obstacle_density: f64,
}

impl RandomMap {
    /// Check the parameters.
    ///
    /// ```
    /// let p = mdp::RandomMap { width: 1, height: 1, obstacle_density: 0.0 };
    /// assert!(p.validate().is_err()); // no room for a goal and a state
    /// ```
    pub fn validate(&self) -> Result<(), MapError> {
        let bad = |name, reason: String| Err(MapError::InvalidRandomParameter { name, reason });
        if self.width == 0 || self.width > MAX_SIDE {
            return bad("width", format!("{} is not in 1..={MAX_SIDE}", self.width));
        }
        if self.height == 0 || self.height > MAX_SIDE {
            return bad(
                "height",
                format!("{} is not in 1..={MAX_SIDE}", self.height),
            );
        }
        if self.width * self.height < 2 {
            return bad("width", "a map needs at least 2 cells".to_string());
        }
        if !(0.0..1.0).contains(&self.obstacle_density) {
            return bad(
                "obstacle_density",
                format!("{} is not in [0, 1)", self.obstacle_density),
            );
        }
        Ok(())
    }

    /// Draw a valid map: the goal on a uniformly random cell, obstacles on a uniformly
    /// random subset of the other cells, then every free cell cut off from the goal filled
    /// in. If that leaves no empty cell, one neighbour of the goal is cleared. The result
    /// is a pure function of the parameters and the generator's state.
    ///
    /// ```
    /// use rand::SeedableRng;
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(7);
    /// let p = mdp::RandomMap { width: 10, height: 6, obstacle_density: 0.3 };
    /// let map = p.generate("r", &mut rng).unwrap();
    /// assert_eq!((map.width(), map.height()), (10, 6));
    /// ```
    pub fn generate<R: Rng + ?Sized>(&self, name: &str, rng: &mut R) -> Result<Map, MapError> {
        self.validate()?;
        let (w, h) = (self.width, self.height);
        let n = w * h;
        let goal = rng.random_range(0..n);
        let mut cells = vec![Cell::Empty; n];
        cells[goal] = Cell::Goal;
        let mut others: Vec<usize> = (0..n).filter(|&i| i != goal).collect();
        others.shuffle(rng);
        let k = (self.obstacle_density * (n - 1) as f64).round() as usize;
        for &i in others.iter().take(k.min(n - 2)) {
            cells[i] = Cell::Obstacle;
        }
        // Keep only the goal's component.
        let mut seen = vec![false; n];
        seen[goal] = true;
        let mut queue = VecDeque::from([goal]);
        while let Some(i) = queue.pop_front() {
            let (r, c) = (i / w, i % w);
            let mut visit = |j: usize| {
                if !seen[j] && cells[j] != Cell::Obstacle {
                    seen[j] = true;
                    queue.push_back(j);
                }
            };
            if r > 0 {
                visit(i - w);
            }
            if r + 1 < h {
                visit(i + w);
            }
            if c > 0 {
                visit(i - 1);
            }
            if c + 1 < w {
                visit(i + 1);
            }
        }
        for (i, cell) in cells.iter_mut().enumerate() {
            if !seen[i] {
                *cell = Cell::Obstacle;
            }
        }
        if !cells.contains(&Cell::Empty) {
            let (r, c) = (goal / w, goal % w);
            let mut nbrs = Vec::with_capacity(4);
            if r > 0 {
                nbrs.push(goal - w);
            }
            if r + 1 < h {
                nbrs.push(goal + w);
            }
            if c > 0 {
                nbrs.push(goal - 1);
            }
            if c + 1 < w {
                nbrs.push(goal + 1);
            }
            let j = nbrs[rng.random_range(0..nbrs.len())];
            cells[j] = Cell::Empty;
        }
        let description = format!(
            "A random {w} by {h} map with obstacle density {}.",
            // Adding 0 turns a density of -0 into 0, so no "-0" is ever printed.
            self.obstacle_density + 0.0
        );
        Ok(Map::from_parts(
            name.to_string(),
            Some(description),
            w,
            cells,
        ))
    }
}
