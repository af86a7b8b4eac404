//! Progress shown on long work.

/// A sign of life on long work: a bar on a terminal's stderr, nothing otherwise.
pub(crate) fn progress_bar(len: usize) -> indicatif::ProgressBar {
    indicatif::ProgressBar::with_draw_target(
        Some(len as u64),
        indicatif::ProgressDrawTarget::stderr(),
    )
}
