//! A run priced by `[costly]` and stopped from outside says in its report that its
//! costed returns are missing and why, instead of leaving them out without a word.

use csql::{Flow, Observer, RunSettings, Setup, StrategyKind, TracePoint};

/// Stops the run after `after` trials, as Ctrl-C or SIGTERM does (and says no from then
/// on, as the program's observer does once the signal came).
struct StopAfter {
    after: u32,
    seen: u32,
}

impl Observer for StopAfter {
    fn keep_trace(&self) -> bool {
        false
    }

    fn trial(&mut self, _: &TracePoint) -> Flow {
        self.seen += 1;
        if self.keep_going() {
            Flow::Continue
        } else {
            Flow::Stop
        }
    }

    fn keep_going(&mut self) -> bool {
        self.seen < self.after
    }
}

fn priced() -> RunSettings {
    let mut s = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 1);
    s.costly = Some(csql::CostlySettings::new(0.01));
    s
}

#[test]
fn a_priced_run_stopped_from_outside_says_its_costed_returns_are_missing() {
    let settings = priced();
    let setup = Setup::new(&settings).unwrap();
    let report =
        csql::run_observed(&setup, &settings, &mut StopAfter { after: 3, seen: 0 }).unwrap();
    assert_eq!(report.trials, 3);
    assert!(report.costly.is_none());
    let why = report.costly_missing.as_deref().expect("a reason");
    assert!(
        why.contains("stopped") && why.contains("max_trials = 3"),
        "{why}"
    );
    let json = serde_json::to_value(&report).unwrap();
    assert!(json["costly_missing"].is_string(), "{json}");
}

#[test]
fn a_priced_run_not_stopped_has_its_costed_returns_and_no_note() {
    let settings = priced();
    let setup = Setup::new(&settings).unwrap();
    let report = csql::run_observed(
        &setup,
        &settings,
        &mut StopAfter {
            after: u32::MAX,
            seen: 0,
        },
    )
    .unwrap();
    let costly = report.costly.as_ref().expect("costed returns");
    assert_eq!(costly.returns.len(), report.trials as usize);
    assert!(report.costly_missing.is_none());
    let json = serde_json::to_value(&report).unwrap();
    assert!(json.get("costly_missing").is_none(), "{json}");
}
