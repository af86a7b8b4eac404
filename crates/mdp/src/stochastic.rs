//! Beyond determinism: slippery moves and noisy sensors, each a validated probability,
//! and the stochastic MDP view the oracle solves and policies are evaluated on.
//!
//! The deterministic [`Mdp`] trait stays as it is for code that relies on determinism
//! (the paper's theorems, the incremental judge). A stochastic world is a
//! [`StochasticMdp`]: it lists the outcomes of an action with their probabilities (for
//! the oracle's value iteration and exact policy evaluation) and samples one with an
//! RNG passed in (for learning). A [`GridWorld`] is a `StochasticMdp` with one outcome
//! per action; a [`SlipperyGrid`] borrows a grid world and reuses its deterministic moves
//! for the slips, so no grid is written twice.

use rand::{Rng, RngExt};
use serde::{Deserialize, Serialize};

use crate::error::MdpError;
use crate::geometry::Cell;
use crate::grid::{Action, GridWorld};
use crate::process::{ActionId, Mdp, StateId, Step};
use crate::sensing::Reading;

fn probability(name: &'static str, value: f64) -> Result<f64, MdpError> {
    if (0.0..=1.0).contains(&value) {
        Ok(value)
    } else {
        Err(MdpError::InvalidProbability { name, value })
    }
}

/// The probability that a move slips to one of its two perpendicular directions (half
/// each), as in slippery frozen-lake grids. 0 is the paper's deterministic world.
///
/// ```
/// let s = mdp::Slip::new(0.1).unwrap();
/// assert_eq!(s.get(), 0.1);
/// assert!(mdp::Slip::new(1.5).unwrap_err().to_string().contains("slip = 1.5"));
/// assert!(mdp::Slip::default().is_zero());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct Slip(f64);

impl Slip {
    /// A slip probability in `[0, 1]`.
    ///
    /// ```
    /// assert!(mdp::Slip::new(-0.1).is_err());
    /// ```
    pub fn new(p: f64) -> Result<Slip, MdpError> {
        probability("slip", p).map(Slip)
    }
    /// The probability.
    ///
    /// ```
    /// assert_eq!(mdp::Slip::new(0.2).unwrap().get(), 0.2);
    /// ```
    pub fn get(self) -> f64 {
        self.0
    }
    /// Whether moves never slip.
    ///
    /// ```
    /// assert!(!mdp::Slip::new(0.05).unwrap().is_zero());
    /// ```
    pub fn is_zero(&self) -> bool {
        self.0 == 0.0
    }
}

impl TryFrom<f64> for Slip {
    type Error = MdpError;
    fn try_from(p: f64) -> Result<Slip, MdpError> {
        Slip::new(p)
    }
}

impl From<Slip> for f64 {
    fn from(s: Slip) -> f64 {
        s.0
    }
}

/// The probability that a measurement returns one of the other cell conditions
/// (uniformly) instead of the true one. A wrong measurement is charged like a right one.
///
/// ```
/// use mdp::{Cell, SensorNoise};
/// use rand::SeedableRng;
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let always = SensorNoise::new(1.0).unwrap();
/// assert_ne!(always.corrupt(Cell::Empty, &mut rng), Cell::Empty);
/// // Noise 0 never draws from the generator.
/// assert_eq!(SensorNoise::default().corrupt(Cell::Goal, &mut rng), Cell::Goal);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct SensorNoise(f64);

impl SensorNoise {
    /// A noise probability in `[0, 1]`.
    ///
    /// ```
    /// assert!(mdp::SensorNoise::new(f64::NAN).is_err());
    /// ```
    pub fn new(p: f64) -> Result<SensorNoise, MdpError> {
        probability("sensor_noise", p).map(SensorNoise)
    }
    /// The probability.
    ///
    /// ```
    /// assert_eq!(mdp::SensorNoise::new(0.05).unwrap().get(), 0.05);
    /// ```
    pub fn get(self) -> f64 {
        self.0
    }
    /// Whether sensing is exact.
    ///
    /// ```
    /// assert!(mdp::SensorNoise::default().is_zero());
    /// ```
    pub fn is_zero(&self) -> bool {
        self.0 == 0.0
    }

    /// What a sensor reports when the cell's true condition is `truth`. With noise 0
    /// nothing is drawn; otherwise one uniform `f64`, and a `random_range(0..2)` to pick
    /// among the two other conditions when the measurement is wrong.
    ///
    /// ```
    /// use mdp::{Cell, SensorNoise};
    /// use rand::SeedableRng;
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(7);
    /// let noise = SensorNoise::new(0.5).unwrap();
    /// let wrong = (0..1000).filter(|_| noise.corrupt(Cell::Empty, &mut rng) != Cell::Empty).count();
    /// assert!((400..600).contains(&wrong));
    /// ```
    pub fn corrupt<R: Rng + ?Sized>(self, truth: Cell, rng: &mut R) -> Cell {
        let read = self.corrupt_reading(Reading::from(truth), Cell::ALL.len() as u32, rng);
        Cell::try_from(read).unwrap_or(truth)
    }

    /// What a sensor reports when the true reading is `truth`, one of `0..readings`. With
    /// noise 0 nothing is drawn; otherwise one uniform `f64`, and, when the measurement
    /// is wrong, a `random_range(0..readings - 1)` to pick among the other readings in
    /// ascending order (on a grid's three conditions, exactly [`SensorNoise::corrupt`]).
    /// A feature with a single reading reads it whatever the noise.
    ///
    /// ```
    /// use mdp::{Reading, SensorNoise};
    /// use rand::SeedableRng;
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(7);
    /// let noise = SensorNoise::new(1.0).unwrap();
    /// assert!((0..100).all(|_| noise.corrupt_reading(Reading(4), 8, &mut rng) != Reading(4)));
    /// assert_eq!(noise.corrupt_reading(Reading(0), 1, &mut rng), Reading(0));
    /// ```
    pub fn corrupt_reading<R: Rng + ?Sized>(
        self,
        truth: Reading,
        readings: u32,
        rng: &mut R,
    ) -> Reading {
        if self.is_zero() || rng.random::<f64>() >= self.0 || readings < 2 {
            return truth;
        }
        let mut others = (0..readings).map(Reading).filter(|&r| r != truth);
        let pick = rng.random_range(0..(readings - 1) as usize);
        others.nth(pick).unwrap_or(truth)
    }
}

impl SensorNoise {
    /// Read a condition `reads` times (each read noisy, independently) and report the
    /// value read most often; ties go to the value first read among the tied. One read
    /// is [`SensorNoise::corrupt`], with the same draws. With noise `p` and three reads a
    /// value is wrong with probability about `1.5 p^2` instead of `p`.
    ///
    /// ```
    /// use mdp::{Cell, SensorNoise};
    /// use rand::SeedableRng;
    /// let noise = SensorNoise::new(0.1).unwrap();
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(3);
    /// let wrong = |reads: u32, rng: &mut rand_xoshiro::Xoshiro256PlusPlus| {
    ///     (0..10_000).filter(|_| noise.majority(Cell::Empty, reads, rng) != Cell::Empty).count()
    /// };
    /// let (one, three) = (wrong(1, &mut rng), wrong(3, &mut rng));
    /// assert!(one > 800 && one < 1200, "{one}");
    /// assert!(three < 250, "{three}");
    /// ```
    pub fn majority<R: Rng + ?Sized>(self, truth: Cell, reads: u32, rng: &mut R) -> Cell {
        let read = self.majority_reading(Reading::from(truth), Cell::ALL.len() as u32, reads, rng);
        Cell::try_from(read).unwrap_or(truth)
    }

    /// [`SensorNoise::majority`] over the readings `0..readings` of any feature, with the
    /// draws of [`SensorNoise::corrupt_reading`].
    ///
    /// ```
    /// use mdp::{Reading, SensorNoise};
    /// use rand::SeedableRng;
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(3);
    /// let noise = SensorNoise::new(0.1).unwrap();
    /// let wrong = (0..1000).filter(|_| noise.majority_reading(Reading(2), 5, 3, &mut rng) != Reading(2)).count();
    /// assert!(wrong < 100, "{wrong}");
    /// ```
    pub fn majority_reading<R: Rng + ?Sized>(
        self,
        truth: Reading,
        readings: u32,
        reads: u32,
        rng: &mut R,
    ) -> Reading {
        if reads <= 1 {
            return self.corrupt_reading(truth, readings, rng);
        }
        let mut seen: Vec<(Reading, u32)> = Vec::with_capacity(3);
        for _ in 0..reads {
            let v = self.corrupt_reading(truth, readings, rng);
            match seen.iter_mut().find(|(c, _)| *c == v) {
                Some((_, n)) => *n += 1,
                None => seen.push((v, 1)),
            }
        }
        let most = seen.iter().map(|&(_, n)| n).max().unwrap_or(0);
        seen.iter()
            .find(|&&(_, n)| n == most)
            .map_or(truth, |&(c, _)| c)
    }
}

impl TryFrom<f64> for SensorNoise {
    type Error = MdpError;
    fn try_from(p: f64) -> Result<SensorNoise, MdpError> {
        SensorNoise::new(p)
    }
}

impl From<SensorNoise> for f64 {
    fn from(s: SensorNoise) -> f64 {
        s.0
    }
}

/// A finite MDP whose actions may have several outcomes.
///
/// [`StochasticMdp::outcomes`] is the true model (the oracle and exact policy evaluation
/// read it); [`StochasticMdp::sample`] draws one outcome with the caller's generator
/// (learning uses it). Outcomes' probabilities sum to 1.
///
/// ```
/// use mdp::{GridWorld, Slip, SlipperyGrid, StochasticMdp};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let slippery = SlipperyGrid::new(&world, Slip::new(0.2).unwrap());
/// let mut out = Vec::new();
/// slippery.outcomes(world.states()[0], mdp::Action::Right.id(), &mut out);
/// let total: f64 = out.iter().map(|o| o.0).sum();
/// assert!((total - 1.0).abs() < 1e-12);
/// ```
pub trait StochasticMdp {
    /// The number of states; ids are `0..num_states()`.
    fn num_states(&self) -> usize;
    /// The number of actions, the same in every state; ids are `0..num_actions()`.
    fn num_actions(&self) -> usize;
    /// Whether `s` is terminal (no action is taken there).
    fn is_terminal(&self, s: StateId) -> bool;
    /// The outcomes of `a` in `s` with their probabilities, written into `out` (cleared
    /// first); outcomes may repeat a next state.
    fn outcomes(&self, s: StateId, a: ActionId, out: &mut Vec<(f64, Step)>);
    /// Draw one outcome of `a` in `s`.
    fn sample<R: Rng + ?Sized>(&self, s: StateId, a: ActionId, rng: &mut R) -> Step;
}

impl StochasticMdp for GridWorld {
    fn num_states(&self) -> usize {
        Mdp::num_states(self)
    }
    fn num_actions(&self) -> usize {
        4
    }
    fn is_terminal(&self, s: StateId) -> bool {
        Mdp::is_terminal(self, s)
    }
    fn outcomes(&self, s: StateId, a: ActionId, out: &mut Vec<(f64, Step)>) {
        out.clear();
        out.push((1.0, self.step(s, a)));
    }
    /// Deterministic: draws nothing.
    fn sample<R: Rng + ?Sized>(&self, s: StateId, a: ActionId, _rng: &mut R) -> Step {
        self.step(s, a)
    }
}

/// The two directions perpendicular to a move, in id order.
pub(crate) fn perpendicular(a: Action) -> [Action; 2] {
    match a {
        Action::Up | Action::Down => [Action::Left, Action::Right],
        Action::Left | Action::Right => [Action::Up, Action::Down],
    }
}

/// A grid world whose moves slip: with probability `slip` a move goes to one of its two
/// perpendicular directions instead, half each (the slipped move is the grid's own
/// deterministic move in that direction: blocked slips stay, a slip into the goal pays).
///
/// Sampling with slip 0 draws nothing, so a run on a `SlipperyGrid` with slip 0 is the
/// run on its grid world, draw for draw. With slip above 0, each move draws one uniform
/// `f64`: below `slip / 2` the first perpendicular direction (up or left), below `slip`
/// the second (down or right), otherwise the intended move.
///
/// ```
/// use mdp::{Action, GridWorld, Pos, Slip, SlipperyGrid, StochasticMdp};
/// use rand::SeedableRng;
/// let world = GridWorld::new(&mdp::builtin("tan8x8").unwrap());
/// let slippery = SlipperyGrid::new(&world, Slip::new(1.0).unwrap());
/// let s = world.state_at(Pos::new(7, 0)).unwrap();
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// // With slip 1 an "up" never goes up.
/// let up = mdp::Mdp::step(&world, s, Action::Up.id()).next;
/// assert!((0..20).all(|_| slippery.sample(s, Action::Up.id(), &mut rng).next != up || up == s));
/// ```
#[derive(Clone, Copy, Debug)]
pub struct SlipperyGrid<'w> {
    world: &'w GridWorld,
    slip: Slip,
}

impl<'w> SlipperyGrid<'w> {
    /// A grid world with slippery moves.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let g = mdp::SlipperyGrid::new(&w, mdp::Slip::new(0.1).unwrap());
    /// assert_eq!(g.slip().get(), 0.1);
    /// ```
    pub fn new(world: &'w GridWorld, slip: Slip) -> SlipperyGrid<'w> {
        SlipperyGrid { world, slip }
    }
    /// The grid world underneath.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let g = mdp::SlipperyGrid::new(&w, mdp::Slip::default());
    /// assert_eq!(g.world().map().name(), "tan3x3");
    /// ```
    pub fn world(&self) -> &'w GridWorld {
        self.world
    }
    /// The slip probability.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// assert!(mdp::SlipperyGrid::new(&w, mdp::Slip::default()).slip().is_zero());
    /// ```
    pub fn slip(&self) -> Slip {
        self.slip
    }
}

impl StochasticMdp for SlipperyGrid<'_> {
    fn num_states(&self) -> usize {
        Mdp::num_states(self.world)
    }
    fn num_actions(&self) -> usize {
        4
    }
    fn is_terminal(&self, s: StateId) -> bool {
        Mdp::is_terminal(self.world, s)
    }
    fn outcomes(&self, s: StateId, a: ActionId, out: &mut Vec<(f64, Step)>) {
        out.clear();
        let p = self.slip.get();
        let Some(act) = Action::from_id(a) else {
            out.push((1.0, self.world.step(s, a)));
            return;
        };
        out.push((1.0 - p, self.world.step(s, a)));
        if p > 0.0 {
            for side in perpendicular(act) {
                out.push((p / 2.0, self.world.step(s, side.id())));
            }
        }
    }
    fn sample<R: Rng + ?Sized>(&self, s: StateId, a: ActionId, rng: &mut R) -> Step {
        let p = self.slip.get();
        if p == 0.0 {
            return self.world.step(s, a);
        }
        let u = rng.random::<f64>();
        let taken = match Action::from_id(a) {
            Some(act) if u < p / 2.0 => perpendicular(act)[0].id(),
            Some(act) if u < p => perpendicular(act)[1].id(),
            _ => a,
        };
        self.world.step(s, taken)
    }
}

/// The value of a fixed policy in a world where each of its actions has a single
/// outcome, by following each state's path to its end and backing the rewards up along
/// it: linear in the number of states, where [`evaluate_policy`] sweeps them until
/// nothing changes. Each value is `r + gamma * v(next)` computed once its successor's is
/// final, so where every path ends within a few hundred moves the two agree bit for bit
/// (beyond that, [`evaluate_policy`] stops at a change of 1e-13 and this one keeps the
/// last digits). A loop that earns nothing is worth 0, as sweeping finds. `Ok(None)`
/// where an action of the policy has several outcomes or a loop earns a reward:
/// [`evaluate_policy`] values those.
///
/// ```
/// use mdp::{ActionId, GridWorld, Oracle, StateId};
/// let world = GridWorld::new(&mdp::builtin("tan8x8").unwrap());
/// let oracle = Oracle::for_grid(&world, 0.9).unwrap();
/// let n = mdp::StochasticMdp::num_states(&world);
/// let best: Vec<_> = (0..n as u32).map(|s| oracle.optimal_actions(StateId(s))
///     .first().copied().unwrap_or(ActionId(0))).collect();
/// let v = mdp::follow_policy(&world, 0.9, &best).unwrap().unwrap();
/// assert_eq!(v, mdp::evaluate_policy(&world, 0.9, &best).unwrap());
/// // Always "up" walks into walls and stays there: a loop that earns nothing.
/// let up = vec![ActionId(0); n];
/// assert_eq!(mdp::follow_policy(&world, 0.9, &up).unwrap().unwrap(), mdp::evaluate_policy(&world, 0.9, &up).unwrap());
/// ```
pub fn follow_policy<M: StochasticMdp + ?Sized>(
    mdp: &M,
    gamma: f64,
    policy: &[ActionId],
) -> Result<Option<Vec<f64>>, MdpError> {
    check_policy(mdp, gamma, policy)?;
    let n = mdp.num_states();
    const NEW: u8 = 0;
    const ON_PATH: u8 = 1;
    const DONE: u8 = 2;
    let mut v = vec![0.0; n];
    let mut mark: Vec<u8> = (0..n)
        .map(|s| {
            if mdp.is_terminal(StateId(s as u32)) {
                DONE
            } else {
                NEW
            }
        })
        .collect();
    let mut path: Vec<(usize, (f64, Step))> = Vec::new();
    let mut out = Vec::new();
    for start in 0..n {
        let mut s = start;
        while mark[s] == NEW {
            mark[s] = ON_PATH;
            mdp.outcomes(StateId(s as u32), policy[s], &mut out);
            let [outcome] = out[..] else {
                return Ok(None);
            };
            path.push((s, outcome));
            let step = outcome.1;
            if step.terminated {
                break;
            }
            s = step.next.index();
            if mark[s] == ON_PATH {
                // A loop: worth exactly 0 when it earns nothing (as sweeping finds: its
                // values start at 0 and stay there); otherwise left to the sweep.
                let at = path.iter().rposition(|&(x, _)| x == s).unwrap_or(0);
                if path[at..].iter().any(|(_, (_, step))| step.reward != 0.0) {
                    return Ok(None);
                }
                for (x, _) in path.drain(at..) {
                    mark[x] = DONE;
                }
                break;
            }
        }
        while let Some((x, outcome)) = path.pop() {
            v[x] = backup(&[outcome], &v, gamma);
            mark[x] = DONE;
        }
    }
    Ok(Some(v))
}

/// The value of a fixed policy (one action per state) from every state, on the true
/// model, by iterating its Bellman equation until nothing changes by more than 1e-13
/// (exact up to rounding; terminal states have value 0).
///
/// ```
/// use mdp::{GridWorld, Oracle, Slip, SlipperyGrid};
/// let world = GridWorld::new(&mdp::builtin("tan8x8").unwrap());
/// let model = SlipperyGrid::new(&world, Slip::new(0.1).unwrap());
/// let oracle = Oracle::solve_stochastic(&model, 0.9).unwrap();
/// let best: Vec<_> = (0..51).map(|s| oracle.optimal_actions(mdp::StateId(s))
///     .first().copied().unwrap_or(mdp::ActionId(0))).collect();
/// let v = mdp::evaluate_policy(&model, 0.9, &best).unwrap();
/// for s in world.states() { assert!((v[s.index()] - oracle.v_star(s)).abs() < 1e-9); }
/// ```
pub fn evaluate_policy<M: StochasticMdp + ?Sized>(
    mdp: &M,
    gamma: f64,
    policy: &[ActionId],
) -> Result<Vec<f64>, MdpError> {
    check_policy(mdp, gamma, policy)?;
    iterate_bellman(mdp, |s, v, out| {
        mdp.outcomes(s, policy[s.index()], out);
        backup(out, v, gamma)
    })
}

/// The value of a stochastic policy (for every state, a probability per action) from
/// every state, on the true model, as [`evaluate_policy`] computes it. Actions of
/// probability 0 are never looked at, so a policy whose probabilities are all 0 or 1
/// gives exactly what [`evaluate_policy`] gives.
///
/// ```
/// use mdp::{ActionId, GridWorld, Slip, SlipperyGrid};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let model = SlipperyGrid::new(&world, Slip::new(0.1).unwrap());
/// let fixed = vec![ActionId(1); 9];
/// let one_hot: Vec<Vec<f64>> = (0..9).map(|_| vec![0.0, 1.0, 0.0, 0.0]).collect();
/// assert_eq!(
///     mdp::evaluate_policy(&model, 0.9, &fixed).unwrap(),
///     mdp::evaluate_stochastic_policy(&model, 0.9, &one_hot).unwrap(),
/// );
/// let uniform: Vec<Vec<f64>> = (0..9).map(|_| vec![0.25; 4]).collect();
/// let v = mdp::evaluate_stochastic_policy(&model, 0.9, &uniform).unwrap();
/// assert!(v.iter().all(|&x| (0.0..=1.0).contains(&x)));
/// assert!(mdp::evaluate_stochastic_policy(&model, 0.9, &uniform[..3]).is_err());
/// ```
pub fn evaluate_stochastic_policy<M: StochasticMdp + ?Sized>(
    mdp: &M,
    gamma: f64,
    policy: &[Vec<f64>],
) -> Result<Vec<f64>, MdpError> {
    if !(0.0..1.0).contains(&gamma) {
        return Err(MdpError::InvalidDiscount { gamma });
    }
    let (n, na) = (mdp.num_states(), mdp.num_actions());
    let bad = |p: &Vec<f64>| {
        p.len() != na
            || p.iter().any(|x| !(0.0..=1.0).contains(x))
            || (p.iter().sum::<f64>() - 1.0).abs() > 1e-9
    };
    if policy.len() != n || policy.iter().any(bad) {
        return Err(MdpError::BadPolicy {
            found: policy.len(),
            states: n,
            actions: na,
        });
    }
    iterate_bellman(mdp, |s, v, out| {
        let mut value = 0.0;
        for (a, &p) in policy[s.index()].iter().enumerate() {
            if p > 0.0 {
                mdp.outcomes(s, ActionId(a as u32), out);
                value += p * backup(out, v, gamma);
            }
        }
        value
    })
}

/// Iterate `v(s) <- value(s, v)` over the non-terminal states, in place, until nothing
/// changes by more than 1e-13.
fn iterate_bellman<M: StochasticMdp + ?Sized>(
    mdp: &M,
    value: impl Fn(StateId, &[f64], &mut Vec<(f64, Step)>) -> f64,
) -> Result<Vec<f64>, MdpError> {
    let n = mdp.num_states();
    let mut v = vec![0.0; n];
    let mut out = Vec::new();
    loop {
        let mut change: f64 = 0.0;
        for s in 0..n {
            let sid = StateId(s as u32);
            if mdp.is_terminal(sid) {
                continue;
            }
            let x = value(sid, &v, &mut out);
            change = change.max((x - v[s]).abs());
            v[s] = x;
        }
        if change <= 1e-13 {
            return Ok(v);
        }
    }
}

/// A discount in [0, 1) and one valid action per state, or the error that says which is
/// wrong.
fn check_policy<M: StochasticMdp + ?Sized>(
    mdp: &M,
    gamma: f64,
    policy: &[ActionId],
) -> Result<(), MdpError> {
    if !(0.0..1.0).contains(&gamma) {
        return Err(MdpError::InvalidDiscount { gamma });
    }
    let (n, na) = (mdp.num_states(), mdp.num_actions());
    if policy.len() != n || policy.iter().any(|a| a.index() >= na) {
        return Err(MdpError::BadPolicy {
            found: policy.len(),
            states: n,
            actions: na,
        });
    }
    Ok(())
}

/// The expected reward plus discounted value of a list of outcomes.
pub(crate) fn backup(outcomes: &[(f64, Step)], v: &[f64], gamma: f64) -> f64 {
    outcomes
        .iter()
        .map(|(p, step)| {
            p * (step.reward
                + if step.terminated {
                    0.0
                } else {
                    gamma * v[step.next.index()]
                })
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Oracle, builtin};
    use rand::SeedableRng;
    use rand_xoshiro::Xoshiro256PlusPlus;

    #[test]
    fn slip_zero_is_the_grid_and_draws_nothing() {
        let world = GridWorld::new(&builtin("tan8x8").unwrap());
        let model = SlipperyGrid::new(&world, Slip::default());
        let mut a = Xoshiro256PlusPlus::seed_from_u64(3);
        let b = a.clone();
        for s in world.states() {
            for act in Action::ALL {
                assert_eq!(model.sample(s, act.id(), &mut a), world.step(s, act.id()));
            }
        }
        assert_eq!(a, b);
    }

    #[test]
    fn slips_go_sideways_half_each() {
        let world = GridWorld::new(&builtin("open8x8").unwrap());
        let model = SlipperyGrid::new(&world, Slip::new(0.2).unwrap());
        let s = world.state_at(crate::Pos::new(4, 4)).unwrap();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
        let mut counts = [0u32; 4];
        for _ in 0..20000 {
            let next = model.sample(s, Action::Up.id(), &mut rng).next;
            let which = Action::ALL
                .iter()
                .position(|a| world.step(s, a.id()).next == next)
                .unwrap();
            counts[which] += 1;
        }
        assert_eq!(counts[1], 0, "never backwards");
        assert!((15600..16400).contains(&counts[0]), "{counts:?}");
        assert!((1800..2200).contains(&counts[2]) && (1800..2200).contains(&counts[3]));
    }

    #[test]
    fn first_draws_are_pinned() {
        let world = GridWorld::new(&builtin("open8x8").unwrap());
        let model = SlipperyGrid::new(&world, Slip::new(0.5).unwrap());
        let s = world.state_at(crate::Pos::new(4, 4)).unwrap();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(42);
        let got: Vec<u32> = (0..8)
            .map(|_| model.sample(s, Action::Up.id(), &mut rng).next.0)
            .collect();
        let noise = SensorNoise::new(0.5).unwrap();
        let cells: Vec<Cell> = (0..8)
            .map(|_| noise.corrupt(Cell::Empty, &mut rng))
            .collect();
        assert_eq!(got, PINNED_SLIPS);
        assert_eq!(cells, PINNED_CELLS);
    }

    /// Value stability: a change of generator or of the drawing scheme fails here.
    const PINNED_SLIPS: [u32; 8] = [28, 37, 28, 28, 28, 28, 35, 28];
    const PINNED_CELLS: [Cell; 8] = [
        Cell::Goal,
        Cell::Empty,
        Cell::Empty,
        Cell::Empty,
        Cell::Obstacle,
        Cell::Empty,
        Cell::Obstacle,
        Cell::Empty,
    ];

    #[test]
    fn value_iteration_on_slip_zero_is_the_deterministic_oracle() {
        let world = GridWorld::new(&builtin("tan8x8").unwrap());
        let a = Oracle::solve_stochastic(&world, 0.9).unwrap();
        let b = Oracle::for_grid(&world, 0.9).unwrap();
        for s in world.states() {
            assert!((a.v_star(s) - b.v_star(s)).abs() < 1e-9);
            assert_eq!(a.optimal_actions(s), b.optimal_actions(s));
        }
    }

    #[test]
    fn slip_lowers_values_and_no_policy_beats_the_oracle() {
        let world = GridWorld::new(&builtin("tan8x8").unwrap());
        let model = SlipperyGrid::new(&world, Slip::new(0.2).unwrap());
        let o = Oracle::solve_stochastic(&model, 0.9).unwrap();
        let d = Oracle::for_grid(&world, 0.9).unwrap();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
        for s in world.states() {
            assert!(o.v_star(s) < d.v_star(s));
        }
        for _ in 0..20 {
            let policy: Vec<ActionId> = (0..51)
                .map(|_| ActionId(rng.random_range(0..4u32)))
                .collect();
            let v = evaluate_policy(&model, 0.9, &policy).unwrap();
            for s in world.states() {
                assert!(v[s.index()] <= o.v_star(s) + 1e-9);
            }
        }
        assert!(evaluate_policy(&model, 0.9, &[ActionId(0)]).is_err());
        assert!(evaluate_policy(&model, 1.0, &vec![ActionId(0); 51]).is_err());
    }
}
