//! Criterion micro-benchmarks of ccdsim, in `benches/`. From this directory: `cargo bench
//! --bench toi` (time of impact per pair kind), `--bench next_event` (all-pairs against bvh on
//! 2D gases), `--bench thesis_scene` (per event and set-up on the thesis scene) and `--bench
//! game_edits` (edits and events in a live world). The library is empty: a cargo package
//! needs one target besides its benches.
