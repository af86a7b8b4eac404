//! Code shared by the integration tests and the examples that check what they pin.

pub mod lookahead;
