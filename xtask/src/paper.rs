//! The paper's Table 1 (Tan, AAAI-91), for comparison. Columns: resetting, lazy, random,
//! eager. Row 8 is given as an upper bound.

/// One row of the paper's table (rows 1 to 8 in order): its values per strategy.
pub struct PaperRow {
    pub values: [&'static str; 4],
}

pub const TABLE1: [PaperRow; 8] = [
    PaperRow {
        values: ["467768", "62984", "37550", "27184"],
    },
    PaperRow {
        values: ["851", "114", "58", "30"],
    },
    PaperRow {
        values: ["506313", "70562", "61051", "88585"],
    },
    PaperRow {
        values: ["927", "127", "91", "86"],
    },
    PaperRow {
        values: ["50", "50", "50", "50"],
    },
    PaperRow {
        values: ["6.4", "6.9", "7.5", "10.2"],
    },
    PaperRow {
        values: ["9.2", "10.6", "12.3", "16.8"],
    },
    PaperRow {
        values: ["≤ 9", "≤ 10", "≤ 11", "≤ 16"],
    },
];

/// The paper's strategy columns, in order.
pub const STRATEGIES: [&str; 4] = ["resetting", "lazy", "random", "eager"];
