//! Dead reckoning on a grid (the `motion` level only): the cells sensed in the last few
//! moves, placed by the robot's own moves, and the charge of a measurement that the
//! memory already holds. Grid-only: it needs the offsets of the paper's local sensing.

use mdp::{Cell, Feature, FeatureSpace, GridWorld, Offset, Reading};

/// The cells sensed in the last few moves, placed by dead reckoning.
#[derive(Clone, Debug)]
pub(crate) struct Memory {
    /// Half the width and height of the area a trial can reach, offsets included.
    half: (i32, i32),
    offsets: Vec<Offset>,
    cells: Vec<Option<(Reading, u32)>>,
    /// The robot's position relative to where the memory was last anchored.
    pos: (i32, i32),
    /// Moves since the memory was anchored.
    now: u32,
    keep: u32,
}

impl Memory {
    pub(crate) fn new(world: &GridWorld, space: &FeatureSpace, keep: u32) -> Memory {
        // Displacements stay within the map and offsets within its bordered size.
        let half = (
            2 * world.map().width() as i32 + 2,
            2 * world.map().height() as i32 + 2,
        );
        let len = ((2 * half.0 + 1) * (2 * half.1 + 1)) as usize;
        Memory {
            half,
            offsets: space.features().map(|f| space.offset(f)).collect(),
            cells: vec![None; len],
            pos: (0, 0),
            now: 0,
            keep,
        }
    }

    pub(crate) fn clear(&mut self) {
        self.cells.fill(None);
        self.pos = (0, 0);
        self.now = 0;
    }

    fn index(&self, o: Offset) -> Option<usize> {
        let (x, y) = (self.pos.0 + o.dx, self.pos.1 + o.dy);
        if x.abs() > self.half.0 || y.abs() > self.half.1 {
            return None;
        }
        Some(((y + self.half.1) * (2 * self.half.0 + 1) + x + self.half.0) as usize)
    }

    /// The cell at offset `o` from the robot, if sensed recently enough.
    fn known(&self, o: Offset) -> Option<Reading> {
        let (cell, when) = self.cells[self.index(o)?]?;
        (self.now - when <= self.keep).then_some(cell)
    }

    fn record(&mut self, o: Offset, cell: Reading) {
        if let Some(i) = self.index(o) {
            self.cells[i] = Some((cell, self.now));
        }
    }

    /// Dead reckoning: the robot moved by `step` unless the cell there is an obstacle. If
    /// it does not remember that cell it cannot tell, and starts over.
    pub(crate) fn moved(&mut self, step: Offset) {
        let ahead = self.known(step);
        self.now += 1;
        match ahead {
            Some(r) if r == Reading::from(Cell::Obstacle) => {}
            Some(_) => self.pos = (self.pos.0 + step.dx, self.pos.1 + step.dy),
            None => self.clear(),
        }
    }
}

/// The charge of `measured` (`full` without a memory): what the memory holds is free,
/// and everything measured or carried is kept for the next state.
pub(crate) fn charge(
    memory: Option<&mut Memory>,
    prices: &[f64],
    measured: &[(Feature, Reading)],
    full: f64,
) -> f64 {
    let Some(memory) = memory else {
        return full;
    };
    let mut cost = 0.0;
    for &(f, cell) in measured {
        let o = memory.offsets[f.index()];
        match memory.known(o) {
            Some(remembered) => {
                debug_assert_eq!(remembered, cell, "dead reckoning placed a cell wrongly");
            }
            None => cost += prices[f.index()],
        }
        memory.record(o, cell);
    }
    cost
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dead_reckoning_moves_unless_blocked_and_forgets_when_unsure() {
        let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
        let space = FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
        let mut m = Memory::new(&world, &space, 1);
        m.record(Offset::new(1, 0), Reading::from(Cell::Empty));
        m.record(Offset::new(2, 0), Reading::from(Cell::Obstacle));
        m.record(Offset::new(0, 1), Reading::from(Cell::Obstacle));
        m.moved(Offset::new(1, 0));
        assert_eq!(
            m.known(Offset::new(1, 0)),
            Some(Reading::from(Cell::Obstacle))
        );
        assert_eq!(
            m.known(Offset::new(-1, 1)),
            Some(Reading::from(Cell::Obstacle))
        );
        m.moved(Offset::new(1, 0)); // blocked: stays
        assert_eq!(m.pos, (1, 0));
        // Sensed two moves ago: forgotten with a memory of one move.
        assert_eq!(m.known(Offset::new(1, 0)), None);
        m.moved(Offset::new(0, -1)); // unknown: starts over
        assert_eq!((m.pos, m.known(Offset::new(-1, 1))), ((0, 0), None));
    }
}
