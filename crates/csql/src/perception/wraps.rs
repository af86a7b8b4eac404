//! A perception built on another: it holds the other and adds what it watches after a
//! move is classified ([`Wraps`]). Every method of [`Perception`], [`Sees`] and
//! [`Describes`] is forwarded to the inner perception by the one impl of each below, so
//! a wrapper writes only what it adds, and a method added to these traits later reaches
//! the inner perception of every wrapper without a line in the wrapper.

use mdp::{ActionId, Reading, SensorNoise, StateId, World};
use qlearn::{QTable, RowId};
use rand::Rng;

use crate::perception::rows::Perception;
use crate::perception::view::{Describes, Sees};

/// A perception that holds another ([`Wraps::Inner`]) and is, through the impls of this
/// module, a [`Perception`], [`Sees`] and [`Describes`] that behave as the inner one, with
/// [`Wraps::after_next`] called after every [`Perception::classify_next`].
///
/// ```
/// use csql::{Classify, Perception, Wraps};
/// /// Counts the moves classified.
/// struct Counted(Classify, u32);
/// impl Wraps for Counted {
///     type Inner = Classify;
///     fn inner(&self) -> &Classify {
///         &self.0
///     }
///     fn inner_mut(&mut self) -> &mut Classify {
///         &mut self.0
///     }
///     fn after_next<W: mdp::World + ?Sized>(&mut self, _world: &W) {
///         self.1 += 1;
///     }
/// }
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let mut p = Counted(Classify::new(&sensed), 0);
/// let mut table = qlearn::QTable::new(4).unwrap();
/// let (row, _) = p.classify(&sensed, mdp::StateId(0), &mut table);
/// let mut rng = rand::SeedableRng::seed_from_u64(1);
/// let rng: &mut rand_xoshiro::Xoshiro256PlusPlus = &mut rng;
/// let (next, _) = p.classify_next(&sensed, row, mdp::ActionId(0), mdp::StateId(1), &mut table, rng);
/// // The inner perception's row (one description, no feature yet), and one move
/// // counted by the wrapper.
/// assert_eq!((next, p.rows(), p.1), (row, 1, 1));
/// ```
pub trait Wraps {
    /// The perception wrapped.
    type Inner: Perception + Sees + Describes;
    /// The perception wrapped.
    fn inner(&self) -> &Self::Inner;
    /// The perception wrapped, to change.
    fn inner_mut(&mut self) -> &mut Self::Inner;
    /// Called after the inner perception classified the state a move reached
    /// ([`Perception::classify_next`]), with the world it was classified in. Nothing by
    /// default.
    fn after_next<W: World + ?Sized>(&mut self, world: &W) {
        let _ = world;
    }
}

impl<T: Wraps> Perception for T {
    fn classify<W: World + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        self.inner_mut().classify(world, s, table)
    }

    fn classify_next<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        from: RowId,
        a: ActionId,
        s: StateId,
        table: &mut QTable,
        rng: &mut R,
    ) -> (RowId, f64) {
        let out = self
            .inner_mut()
            .classify_next(world, from, a, s, table, rng);
        self.after_next(world);
        out
    }

    fn classify_again<W: World + ?Sized>(
        &mut self,
        world: &W,
        refined: RowId,
        current: RowId,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        self.inner_mut()
            .classify_again(world, refined, current, s, table)
    }

    fn updated(
        &mut self,
        row: RowId,
        a: ActionId,
        reward: f64,
        next: Option<RowId>,
        table: &mut QTable,
    ) {
        self.inner_mut().updated(row, a, reward, next, table);
    }

    fn refine<W: World + ?Sized>(&mut self, world: &W, row: RowId, s: StateId) -> Option<f64> {
        self.inner_mut().refine(world, row, s)
    }

    fn rows(&self) -> usize {
        self.inner().rows()
    }

    fn lookup<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> Option<RowId> {
        self.inner_mut().lookup(world, s)
    }

    fn learns_from_move(&self, ended: bool) -> bool {
        self.inner().learns_from_move(ended)
    }

    fn keeps_rows(&self) -> bool {
        self.inner().keeps_rows()
    }
}

impl<T: Wraps> Sees for T {
    fn sees<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        noise: SensorNoise,
        rng: &mut R,
    ) -> Option<RowId> {
        self.inner_mut().sees(world, s, noise, rng)
    }

    fn memoryless(&self) -> bool {
        self.inner().memoryless()
    }

    fn begin(&mut self) {
        self.inner_mut().begin();
    }

    fn moved(&mut self, a: ActionId) {
        self.inner_mut().moved(a);
    }
}

impl<T: Wraps> Describes for T {
    fn described(&self) -> Vec<(RowId, Vec<(mdp::Feature, Reading)>)> {
        self.inner().described()
    }

    fn cost_after_learning<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> f64 {
        self.inner_mut().cost_after_learning(world, s)
    }

    fn table1_costs<W: World + ?Sized>(&mut self, world: &W) -> (f64, f64) {
        self.inner_mut().table1_costs(world)
    }
}
