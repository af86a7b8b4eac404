//! The CSV reader: the first byte splits the input into a data file and a costs file; any
//! bytes give a data set or an error, never a panic.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let Some((&cut, rest)) = data.split_first() else {
        return;
    };
    let cut = usize::from(cut).min(rest.len());
    let (table, costs) = rest.split_at(rest.len() - cut);
    let options = cslearn::DatasetOptions::new("t");
    let _ = cslearn::Dataset::from_readers(table, "fuzz.csv", costs, "costs.csv", &options);
});
