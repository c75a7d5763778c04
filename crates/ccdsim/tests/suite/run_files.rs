//! Run files: round trips, version refusal, truncation at any byte, and determinism.

use ccdsim::generate::{gas, rack, GasConfig, RackConfig};
use ccdsim::record::{
    record_len, RecordError, RunReader, RunRecord, RunWriter, Tail, PREAMBLE_LEN,
};
use ccdsim::{Scene, Simulation};
use rand::{Rng, SeedableRng};
use sha2::{Digest, Sha256};

const TRUNCATION_SEED: u64 = 0x7e57_cafe;

fn record<const D: usize>(scene: &Scene<D>, events: u64, finder: &str) -> Vec<u8> {
    let mut sim = Simulation::new(scene, finder).unwrap();
    let mut w = RunWriter::new(Vec::new(), "memory".into(), scene).unwrap();
    sim.run_events_with(events, |c| w.write_event(c).unwrap());
    w.finish(sim.time()).unwrap()
}

#[test]
fn round_trip_reads_every_event_back() {
    let scene = rack(&RackConfig::default());
    let bytes = record(&scene, 300, "all-pairs");
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let mut r = RunReader::<_, 2>::new(&bytes[..], "memory".into()).unwrap();
    assert_eq!(r.scene(), &scene);
    for _ in 0..300 {
        let want = sim.step_event().unwrap();
        assert_eq!(r.next_record().unwrap(), Some(RunRecord::Event(want)));
    }
    assert_eq!(r.next_record().unwrap(), Some(RunRecord::End(sim.time())));
    assert_eq!(r.next_record().unwrap(), None);
    assert_eq!(r.tail(), Tail::Complete);
}

#[test]
fn refuses_other_versions_and_other_files() {
    let scene = rack(&RackConfig::default());
    let mut bytes = record(&scene, 5, "all-pairs");
    bytes[8] = 99;
    match RunReader::<_, 2>::new(&bytes[..], "x.ccd".into()) {
        // This build reads versions 1 (plain runs) to 3 (runs with growing radii).
        Err(RecordError::Version {
            found: 99,
            supported: ccdsim::record::VERSION_NEWEST,
            ..
        }) => {}
        other => panic!("expected a version error, got {:?}", other.err()),
    }
    let msg = RunReader::<_, 2>::new(&b"{\"dim\": 2}"[..], "x.json".into())
        .err()
        .unwrap()
        .to_string();
    assert!(msg.contains("not a ccdsim run file"), "{msg}");
    let bytes = record(&scene, 5, "all-pairs");
    assert!(
        RunReader::<_, 3>::new(&bytes[..], "x".into()).is_err(),
        "a 2D run is not read as 3D"
    );
}

#[test]
fn refuses_flags_its_format_version_does_not_have() {
    // A plain run (version 1) whose first record claims a resting or turning body: bits
    // only versions 11 and 13 have. The checksum is made right, so only the tag is wrong.
    let scene = rack(&RackConfig::default());
    let clean = record(&scene, 5, "all-pairs");
    let header = u64::from_le_bytes(clean[16..24].try_into().unwrap()) as usize;
    let first = PREAMBLE_LEN + header;
    let len = record_len(2);
    for flag in [0x40u8, 0x20, 0x10] {
        let mut bytes = clean.clone();
        bytes[first] |= flag;
        let sum = fnv1a(&bytes[first..first + len - 4]);
        bytes[first + len - 4..first + len].copy_from_slice(&sum.to_le_bytes());
        let mut r = RunReader::<_, 2>::new(&bytes[..], "x.ccd".into()).unwrap();
        let err = r
            .next_record()
            .expect_err("a flag version 1 lacks")
            .to_string();
        assert!(
            err.contains("bad tag") && err.contains("version 1"),
            "{err}"
        );
    }
}

/// FNV-1a, 32 bits: the run file's record checksum.
fn fnv1a(bytes: &[u8]) -> u32 {
    bytes.iter().fold(0x811c_9dc5u32, |h, &b| {
        (h ^ u32::from(b)).wrapping_mul(0x0100_0193)
    })
}

#[test]
fn truncated_at_any_offset_reads_back_to_the_last_complete_event() {
    let scene: Scene<3> = gas(&GasConfig {
        n: 40,
        packing: 0.2,
        seed: 3,
        ..GasConfig::default()
    })
    .unwrap();
    let bytes = record(&scene, 200, "all-pairs");
    let rec = record_len(3);
    let mut full = RunReader::<_, 3>::new(&bytes[..], "full".into()).unwrap();
    let data_start = full.data_start() as usize;
    let (events, end) = full.read_events().unwrap();
    assert_eq!(events.len(), 200);
    assert!(end.is_some());
    assert_eq!(bytes.len(), data_start + 201 * rec);

    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(TRUNCATION_SEED);
    let mut offsets: Vec<usize> = (0..400).map(|_| rng.random_range(0..bytes.len())).collect();
    offsets.extend([
        0,
        7,
        PREAMBLE_LEN,
        data_start - 1,
        data_start,
        data_start + 1,
        bytes.len() - 1,
    ]);
    for cut in offsets {
        let part = &bytes[..cut];
        match RunReader::<_, 3>::new(part, "cut".into()) {
            Err(e) => assert!(
                cut < data_start,
                "cut at {cut} (data at {data_start}) failed: {e}"
            ),
            Ok(mut r) => {
                assert!(cut >= data_start);
                let (got, end) = r.read_events().unwrap();
                let complete = (cut - data_start) / rec;
                assert_eq!(got.len(), complete.min(200), "cut at {cut}");
                assert_eq!(&got[..], &events[..got.len()]);
                assert_eq!(end, None);
                let partial = (cut - data_start) % rec;
                let want = if partial == 0 {
                    Tail::NoEnd
                } else {
                    Tail::Truncated {
                        bytes: partial as u64,
                    }
                };
                assert_eq!(r.tail(), want, "cut at {cut}");
            }
        }
    }
}

#[test]
fn damage_in_the_middle_is_an_error_naming_the_record() {
    let scene = rack(&RackConfig::default());
    let mut bytes = record(&scene, 50, "all-pairs");
    let mut r = RunReader::<_, 2>::new(&bytes[..], "ok".into()).unwrap();
    let at = r.data_start() as usize + 10 * record_len(2) + 12;
    r.read_events().unwrap();
    bytes[at] ^= 0xff;
    let mut r = RunReader::<_, 2>::new(&bytes[..], "bad.ccd".into()).unwrap();
    let err = r.read_events().unwrap_err().to_string();
    assert!(err.contains("record 10 is corrupt"), "{err}");
}

/// The recorded bytes of a fixed scene never change: any change to the narrow phase, the
/// response, the event order or the format shows up here.
#[test]
fn determinism_golden_hash() {
    let scene = rack(&RackConfig::default());
    let a = record(&scene, 3000, "all-pairs");
    let b = record(&scene, 3000, "all-pairs");
    assert_eq!(a, b, "two runs of the same scene differ");
    let gas3: Scene<3> = gas(&GasConfig {
        n: 60,
        packing: 0.25,
        radius_min: 0.3,
        radius_max: 0.6,
        seed: 11,
        ..GasConfig::default()
    })
    .unwrap();
    let c = record(&gas3, 3000, "all-pairs");
    let hex = |bytes: &[u8]| format!("{:x}", Sha256::digest(bytes));
    assert_eq!(hex(&a), GOLDEN_RACK, "rack run changed");
    assert_eq!(hex(&c), GOLDEN_GAS3, "3D gas run changed");
}

const GOLDEN_RACK: &str = "afcecfe885e98cec4099e9f6f4a2a2a8d5763cb12116b4b7efd6e8dcef071b1e";
const GOLDEN_GAS3: &str = "a7d55125983413fe203bfa08544a1e162797d9ffd28e30934e9809548614cd89";
