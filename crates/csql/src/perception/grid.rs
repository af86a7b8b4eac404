//! Grid-only helpers shared by the learners and the reference points: which features a
//! robot on a grid sees inside the bordered map. Depends on no other module.

use mdp::{FeatureSpace, GridWorld, StateId};

/// The features whose cell, seen from state `s`, lies within `margin` cells of the
/// interior (0: the interior only; 1: the interior and its boundary).
pub(crate) fn bordered_features<'a>(
    world: &'a GridWorld,
    space: &'a FeatureSpace,
    s: StateId,
    margin: i64,
) -> impl Iterator<Item = mdp::Feature> + 'a {
    let p = world.pos(s);
    let (h, w) = (world.map().height() as i64, world.map().width() as i64);
    space.features().filter(move |&f| {
        let o = space.offset(f);
        let (r, c) = (p.row as i64 - o.dy as i64, p.col as i64 + o.dx as i64);
        (-margin..h + margin).contains(&r) && (-margin..w + margin).contains(&c)
    })
}
