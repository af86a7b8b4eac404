//! The yardstick: Boltzmann Q-learning on the open 8 by 8 room written as plainly as
//! possible, over dense arrays, with no abstraction and no caching. The crate's loop
//! must be at least as fast as this.
//!
//! It makes exactly the crate's random draws (one `f64` per move, none for the fixed
//! start) and its arithmetic, so for one seed both produce the same `Q` bit for bit.

use rand::{Rng, RngExt};

/// Side of the room.
const SIDE: usize = 8;
/// Cells; the goal is the last one (bottom-right), the start the first (top-left).
const CELLS: usize = SIDE * SIDE;
const GOAL: usize = CELLS - 1;
const GAMMA: f64 = 0.9;
const T: f64 = 0.4;
const MAX_MOVES: u64 = 100;

/// Run `steps` moves of 100-move trials from the top-left corner; returns the final Q,
/// row-major with the actions up, down, left, right.
pub fn run<R: Rng + ?Sized>(steps: u64, rng: &mut R) -> Vec<f64> {
    // next[s][a]: the cell reached; bumping into the wall stays.
    let mut next = [[0usize; 4]; CELLS];
    for (s, moves) in next.iter_mut().enumerate() {
        let (r, c) = (s / SIDE, s % SIDE);
        *moves = [
            if r > 0 { s - SIDE } else { s },
            if r + 1 < SIDE { s + SIDE } else { s },
            if c > 0 { s - 1 } else { s },
            if c + 1 < SIDE { s + 1 } else { s },
        ];
    }
    let mut q = vec![0.0f64; CELLS * 4];
    let mut v = vec![0.0f64; CELLS];
    let mut s = 0;
    let mut moves = 0;
    for _ in 0..steps {
        let row = &q[s * 4..s * 4 + 4];
        let max = row.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mut w = [0.0; 4];
        let mut total = 0.0;
        for a in 0..4 {
            w[a] = ((row[a] - max) / T).exp();
            total += w[a];
        }
        let u = rng.random::<f64>() * total;
        let mut a = 3;
        let mut acc = 0.0;
        for (b, &wb) in w.iter().enumerate() {
            acc += wb;
            if u < acc {
                a = b;
                break;
            }
        }
        let y = next[s][a];
        let target = if y == GOAL { 1.0 } else { GAMMA * v[y] };
        // With beta = 1, equation 2 is an assignment.
        q[s * 4 + a] = target;
        v[s] = q[s * 4..s * 4 + 4]
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        moves += 1;
        if y == GOAL || moves == MAX_MOVES {
            s = 0;
            moves = 0;
        } else {
            s = y;
        }
    }
    q
}
