//! What several of csql's integration tests share.

/// An observer that says yes to `keep_going` `left` times, then no: a stop asked for
/// where a run does not observe trials (navigation, a long trial, episodes).
pub struct StopAfter {
    pub left: u32,
}

impl csql::Observer for StopAfter {
    fn trial(&mut self, _: &csql::TracePoint) -> csql::Flow {
        csql::Flow::Continue
    }

    fn keep_going(&mut self) -> bool {
        let go = self.left > 0;
        self.left = self.left.saturating_sub(1);
        go
    }
}
