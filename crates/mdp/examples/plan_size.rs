//! The size of a belief plan and the memory it is counted at: a plan from every
//! non-terminal state of a FrozenLake sensed by row and column (0.025 each), with the
//! bound `K` on uncertain steps in a row. Prints what the plan holds
//! ([`mdp::PlanSize`]) and the bytes it is counted at, for measuring a plan's memory
//! beside what the process takes (`/usr/bin/time -v`, docs/costly.md).
//!
//! ```text
//! cargo run --release -p mdp --example plan_size -- WORLD DYNAMICS RULE K [MAX_BELIEFS]
//! ```
//!
//! `WORLD`: `frozenlake4x4` or `frozenlake8x8`; `DYNAMICS`: `deterministic`,
//! `semi-slippery` or `slippery`; `RULE`: `with-move` or `after-outcome`.

use std::process::ExitCode;

use mdp::{
    BeliefPlan, CostlyModel, PlanOptions, ReferenceOptions, SensingMenu, SensingModel, SensingRule,
    StateId, World, WorldOptions,
};

fn main() -> ExitCode {
    match plan(std::env::args().skip(1).collect()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn plan(args: Vec<String>) -> Result<(), Box<dyn std::error::Error>> {
    let usage = "usage: plan_size WORLD DYNAMICS RULE K [MAX_BELIEFS]";
    let [world, dynamics, rule, k, rest @ ..] = args.as_slice() else {
        return Err(usage.into());
    };
    let (slip, slide) = match dynamics.as_str() {
        "deterministic" => (None, None),
        "semi-slippery" => (None, Some(0.5)),
        "slippery" => (Some(2.0 / 3.0), None),
        _ => return Err(usage.into()),
    };
    let rule = match rule.as_str() {
        "with-move" => SensingRule::WithMove,
        "after-outcome" => SensingRule::AfterOutcome,
        _ => return Err(usage.into()),
    };
    let lake = mdp::builtin_world(
        world,
        &WorldOptions {
            slip,
            slide,
            sensing: Some(SensingModel::Factors),
            factor_costs: Some(vec![0.025, 0.025]),
        },
    )?;
    let horizon = if world == "frozenlake8x8" { 200 } else { 100 };
    let mut search = ReferenceOptions {
        horizon,
        max_uncertain: Some(k.parse()?),
        ..ReferenceOptions::default()
    };
    if let Some(cap) = rest.first() {
        search.max_beliefs = cap.parse()?;
    }
    let options = PlanOptions {
        menu: SensingMenu::Features,
        rule,
        search,
        move_cost: 1e-6,
        tolerance: 1e-9,
        blind_plans: 0,
    };
    let model = CostlyModel::of(&lake)?;
    let roots: Vec<StateId> = lake.states();
    let plan = BeliefPlan::build(&model, &options, &roots)?;
    let size = plan.size();
    println!(
        "beliefs {} belief_states {} choices {} edges {} counted_bytes {}",
        size.beliefs,
        size.belief_states,
        size.choices,
        size.edges,
        size.bytes()
    );
    Ok(())
}
