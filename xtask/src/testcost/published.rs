//! The published figures this benchmark is compared with: Esmeir's thesis (Technion,
//! 2008), Tables 4.5 (mc = 500) and 4.6 (mc = 1000), the rows that could be read. Each
//! value is the average total cost as a percentage of the standard cost, the mean of 4
//! random price assignments. Columns: C4.5, LSID3, IDX, CS-ID3, EG2, DTMC, ICET, ACT.

use cslearn::testcost::Method;

/// Table 4.5, misclassification cost 500.
pub const MC500: [(&str, [f64; 8]); 19] = [
    (
        "Breast-cancer",
        [43.3, 42.0, 33.4, 42.7, 33.9, 27.8, 29.1, 28.0],
    ),
    ("Bupa", [90.5, 81.2, 70.6, 82.1, 70.9, 49.6, 51.6, 53.4]),
    ("Car", [49.3, 51.9, 55.2, 49.5, 53.7, 40.1, 48.5, 40.1]),
    ("Flare", [15.0, 15.0, 16.8, 15.4, 16.8, 15.0, 16.5, 15.0]),
    ("Glass", [54.1, 47.2, 42.3, 42.3, 38.9, 37.8, 37.5, 36.6]),
    ("Heart", [42.3, 44.8, 34.5, 39.2, 35.0, 30.2, 29.9, 31.0]),
    (
        "Hepatitis",
        [35.6, 29.6, 20.7, 27.9, 21.3, 13.9, 14.8, 14.8],
    ),
    ("Iris", [30.6, 28.2, 29.0, 27.0, 27.8, 21.7, 22.1, 20.7]),
    ("KRK", [62.4, 64.9, 63.9, 63.5, 63.6, 62.2, 61.9, 59.7]),
    (
        "Multi-ANDOR",
        [47.3, 18.6, 29.3, 31.2, 30.1, 35.7, 19.8, 17.2],
    ),
    ("Monks1", [26.0, 20.0, 25.2, 25.9, 26.0, 53.2, 23.5, 22.8]),
    ("Monks2", [48.9, 66.9, 57.3, 53.8, 55.5, 40.3, 40.3, 40.3]),
    ("Monks3", [35.0, 33.5, 32.7, 32.6, 32.6, 34.6, 32.2, 32.5]),
    (
        "Multiplexer",
        [53.3, 19.3, 39.5, 45.6, 40.2, 39.0, 22.3, 25.3],
    ),
    ("MultiXOR", [60.4, 26.1, 43.2, 51.7, 44.4, 42.9, 43.8, 32.5]),
    ("Nursery", [29.3, 31.1, 29.9, 29.0, 29.2, 31.5, 28.1, 28.8]),
    ("Pima", [73.1, 77.3, 54.5, 68.3, 58.1, 42.0, 45.9, 48.3]),
    ("Tae", [77.2, 67.6, 65.5, 68.2, 67.9, 59.3, 59.7, 58.2]),
    (
        "Tic-tac-toe",
        [55.8, 52.3, 40.2, 49.6, 40.9, 43.9, 42.4, 36.4],
    ),
];

/// Table 4.6, misclassification cost 1000.
pub const MC1000: [(&str, [f64; 8]); 19] = [
    (
        "Breast-cancer",
        [54.3, 56.7, 48.0, 55.4, 48.6, 43.6, 45.2, 45.5],
    ),
    ("Bupa", [91.5, 84.8, 78.4, 85.5, 78.2, 67.2, 69.8, 72.8]),
    ("Car", [41.4, 44.3, 53.8, 42.8, 51.4, 57.2, 41.2, 42.1]),
    ("Flare", [26.0, 26.0, 27.1, 26.3, 27.1, 26.0, 25.9, 26.0]),
    ("Glass", [53.9, 47.2, 55.0, 50.9, 50.2, 49.2, 46.1, 39.7]),
    ("Heart", [45.0, 49.5, 43.0, 44.2, 42.8, 40.3, 41.2, 41.4]),
    (
        "Hepatitis",
        [44.2, 38.1, 31.9, 38.1, 32.2, 28.6, 29.3, 29.7],
    ),
    ("Iris", [22.3, 20.8, 24.1, 21.3, 22.8, 18.9, 16.8, 16.3]),
    ("KRK", [57.8, 63.7, 65.6, 63.6, 64.8, 65.2, 55.1, 55.6]),
    (
        "Multi-ANDOR",
        [47.9, 14.1, 31.5, 32.2, 32.4, 49.0, 16.2, 11.8],
    ),
    ("Monks1", [16.3, 12.2, 15.8, 16.2, 16.3, 52.3, 15.6, 12.2]),
    ("Monks2", [65.4, 77.4, 71.3, 69.4, 70.1, 57.5, 57.5, 57.5]),
    ("Monks3", [23.8, 22.9, 22.5, 22.3, 22.3, 25.5, 22.1, 22.0]),
    (
        "Multiplexer",
        [59.3, 16.2, 51.4, 54.7, 52.0, 57.9, 18.5, 19.9],
    ),
    ("MultiXOR", [62.5, 18.5, 51.0, 56.9, 52.3, 56.7, 49.5, 21.3]),
    ("Nursery", [20.3, 21.6, 21.4, 20.5, 20.8, 24.7, 18.6, 20.2]),
    ("Pima", [74.6, 80.3, 65.6, 71.3, 68.4, 62.3, 60.8, 64.0]),
    ("Tae", [82.1, 73.5, 72.3, 73.6, 74.3, 64.2, 76.8, 67.4]),
    (
        "Tic-tac-toe",
        [53.3, 50.2, 45.6, 48.6, 45.9, 60.9, 44.8, 40.2],
    ),
];

/// The column of a learner of ours in the published tables, if it has one.
pub fn column(method: Method) -> Option<usize> {
    match method {
        Method::C45 => Some(0),
        Method::Idx => Some(2),
        Method::CsId3Batch => Some(3),
        Method::Eg2 => Some(4),
        Method::Dtmc => Some(5),
        Method::Icet => Some(6),
        Method::Act => Some(7),
        Method::Id3 | Method::Cvt | Method::Voi => None,
    }
}

/// The published row of data set `name` (its `published` name) at `mc`, if there is one.
pub fn row(name: &str, mc: f64) -> Option<[f64; 8]> {
    let table: &[(&str, [f64; 8])] = if mc == 500.0 {
        &MC500
    } else if mc == 1000.0 {
        &MC1000
    } else {
        return None;
    };
    table.iter().find(|(n, _)| *n == name).map(|(_, r)| *r)
}
