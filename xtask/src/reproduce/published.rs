//! The paper's figures that the reading of `table1.md` quotes beside ours, on the paper's
//! map only: Tan (AAAI-91), the text around its Table 1 and its Figure 5. The paper's
//! Table 1 itself is csql's (`Table1Row::paper`), one definition for every user of it.
//! Each figure is kept as the paper's words give it, to be quoted as it stands.

/// The cost of sensing every interior cell once from the cheapest state.
pub const CHEAPEST_INTERIOR: &str = "at least 256 on its 8 by 8 map";

/// Resetting's sensing cost to convergence over lazy's and over random's.
pub const RESETTING_OVER_LAZY_RANDOM: &str = "7.2 and 8.3 times";

/// The mean features per description of resetting, lazy, random and eager (row 6).
pub const MEAN_FEATURES: &str = "6.4, 6.9, 7.5, 10.2";

/// The share of the sensing cost to convergence spent learning the representation, per
/// strategy (resetting, lazy, random, eager).
pub const REPRESENTATION_SHARE: &str = "92%, 89%, 62%, 31%, so 30% to 90%";

/// When resetting's cheaper classification pays back its dearer learning.
pub const BREAK_EVEN: &str = "about 220,000 future states";

/// The trials and the sensing cost resetting needs to converge once its representation is
/// sufficient.
pub const RESETTING_AFTER_SUFFICIENT: &str = "76 and 38545";

/// The trials lazy and random need to converge once their representations are sufficient.
pub const HEURISTICS_AFTER_SUFFICIENT: &str = "13 and 29";

/// The descriptions of Figure 5, on the 3 by 3 world.
pub const FIGURE5_DESCRIPTIONS: usize = 7;
