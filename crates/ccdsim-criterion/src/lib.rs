//! Criterion micro-benchmarks of ccdsim, in `benches/`: `cargo bench -p ccdsim-criterion
//! --bench toi` (time of impact per pair kind), `--bench next_event` (all-pairs against bvh on
//! 2D gases), `--bench thesis_scene` (per event and set-up on the thesis scene) and `--bench
//! game_edits` (edits and events in a live world). This library is empty: the crate exists so
//! that the test suite does not compile criterion.
