//! Unit tests of the hierarchy (build, refit, validate, traversal) and of the finder's
//! bookkeeping (options, Δ, caches, termination). Exactness over whole runs is tested for
//! every finder by `tests/finder_suite.rs`.

use super::tree::{swept_box, SweptTree};
use super::*;
use crate::event::EventKind;
use crate::finder::{all_pairs_next_event, make_finder};
use crate::generate::{gas, GasConfig};
use crate::geom::{Aabb, Vector};
use crate::motion::Motion;
use crate::resolve::{resolve_body_body, resolve_body_wall};
use crate::scene::{BodySpec, Scene};
use proptest::prelude::*;

/// Seeds of the generated gases used below.
const SEEDS: [u64; 3] = [11, 2024, 77_777];

/// A polydisperse gas; the packing is lowered for the few small boxes random placement cannot
/// fill (a box for two bodies is barely wider than the larger one).
fn gas_scene<const D: usize>(n: usize, packing: f64, seed: u64) -> Scene<D> {
    let mut packing = packing;
    loop {
        let made = gas(&GasConfig {
            n,
            packing,
            radius_min: 0.3,
            radius_max: 0.8,
            speed_min: 0.0,
            speed_max: 2.0,
            seed,
            ..GasConfig::default()
        });
        match made {
            Ok(scene) => return scene,
            Err(crate::generate::GenerateError::Jammed { .. }) => packing *= 0.5,
            Err(e) => panic!("{e}"),
        }
    }
}

fn world_of<const D: usize>(scene: &Scene<D>) -> World<D> {
    World::from_scene(scene).expect("valid scene")
}

/// Resolves `e` on `world` as the simulation does.
fn resolve<const D: usize>(world: &mut World<D>, e: Event) {
    world.set_now(e.time.max(world.now()));
    match e.kind {
        EventKind::Body => {
            resolve_body_body(world, e.a as usize, e.b as usize, e.time);
        }
        EventKind::Wall => {
            resolve_body_wall(world, e.a as usize, e.b as usize, e.time);
        }
        EventKind::Reset | EventKind::Edit => panic!("finders never predict resets or edits"),
    }
}

fn depth(n: usize) -> u32 {
    (n as f64).log2().ceil() as u32
}

#[test]
fn build_is_valid_and_balanced() {
    for &seed in &SEEDS {
        for n in [1, 2, 3, 4, 5, 7, 8, 9, 31, 64, 100, 257] {
            let w2 = world_of(&gas_scene::<2>(n, 0.3, seed));
            let mut t2 = SweptTree::default();
            t2.build(&w2, 0.0, 0.25);
            t2.validate(&w2).unwrap();
            assert_eq!(t2.nodes.len(), 2 * n - 1);
            let w3 = world_of(&gas_scene::<3>(n, 0.2, seed));
            let mut t3 = SweptTree::default();
            t3.build(&w3, 0.0, 0.25);
            t3.validate(&w3).unwrap();
            let boxes = BvhFinder::<3>::new(&FinderOptions::default())
                .unwrap()
                .debug_boxes(&w3);
            assert_eq!(boxes.len(), 2 * n - 1);
            assert_eq!(boxes.iter().filter(|b| b.leaf).count(), n);
            assert!(boxes.iter().all(|b| b.depth <= depth(n)));
            assert!(boxes
                .iter()
                .filter(|b| b.leaf)
                .all(|b| b.depth + 1 >= depth(n)));
        }
    }
}

#[test]
fn empty_world_builds_an_empty_tree() {
    let w = world_of(&Scene::<2>::default());
    let mut t = SweptTree::default();
    t.build(&w, 0.0, 1.0);
    assert!(t.nodes.is_empty());
    t.validate(&w).unwrap();
    assert!(t.earliest_body_event(&w).best.is_none());
}

#[test]
fn refit_after_growth_is_valid_and_only_grows_boxes() {
    for &seed in &SEEDS {
        let w = world_of(&gas_scene::<2>(200, 0.3, seed));
        let mut t = SweptTree::default();
        t.build(&w, 0.0, 0.01);
        let before = t.nodes.clone();
        t.refit(&w, 0.08);
        t.validate(&w).unwrap();
        for (old, new) in before.iter().zip(&t.nodes) {
            assert!(new.aabb.contains(&old.aabb));
            assert_eq!((old.start, old.count), (new.start, new.count));
        }
        // Refitting back to the build's horizon gives the build's boxes exactly.
        t.refit(&w, 0.01);
        assert_eq!(t.nodes, before);
    }
}

#[test]
fn validate_catches_broken_trees() {
    let w = world_of(&gas_scene::<2>(50, 0.3, SEEDS[0]));
    let mut good = SweptTree::default();
    good.build(&w, 0.0, 0.1);
    good.validate(&w).unwrap();

    let mut shrunk = good.clone();
    shrunk.nodes[0].aabb.max[0] -= 1.0;
    assert!(shrunk.validate(&w).is_err());

    let mut stale_leaf = good.clone();
    let leaf = stale_leaf.nodes.iter().position(|n| n.is_leaf()).unwrap();
    stale_leaf.nodes[leaf].aabb.min[1] += 1e-9;
    assert!(stale_leaf.validate(&w).is_err());

    // Swapping the two ends of the order breaks the median split (and leaf boxes).
    let mut unsplit = good.clone();
    unsplit.order.swap(0, 49);
    assert!(unsplit.validate(&w).is_err());

    let mut short = good.clone();
    short.nodes.pop();
    assert!(short.validate(&w).is_err());

    // A refitted tree no longer claims the median split, but is still checked for the rest.
    let mut refitted = good.clone();
    refitted.refit(&w, 1.0);
    refitted.validate(&w).unwrap();
    refitted.nodes[3].aabb = Aabb::EMPTY;
    assert!(refitted.validate(&w).is_err());
}

#[test]
fn swept_box_holds_the_ball_throughout() {
    let m = Motion {
        pos: Vector([1.0, -2.0, 0.5]),
        vel: Vector([-3.0, 0.25, 1.0]),
        time: 0.5,
    };
    let b = swept_box(&m, 0.1, 1.0, 3.0, None);
    for k in 0..=20 {
        let t = 1.0 + 2.0 * f64::from(k) / 20.0;
        assert!(b.contains(&Aabb::of_ball(m.at(t), 0.1)), "t = {t}");
    }
    // Padded, but by a hair only.
    let tight = Aabb::of_ball(m.at(1.0), 0.1).union(Aabb::of_ball(m.at(3.0), 0.1));
    assert!(b.contains(&tight) && b != tight);
    assert!((b.max[0] - tight.max[0]) < 1e-3);
    // An overflowing position gives a box the tree recognises as non-finite.
    let huge = Motion {
        vel: Vector([1e300, 0.0, 0.0]),
        ..m
    };
    assert!(!tree::is_finite_box(&swept_box(
        &huge, 0.1, 1.0, 1e300, None
    )));
}

#[test]
fn traversal_finds_the_earliest_pair_within_the_horizon() {
    for &seed in &SEEDS {
        let w = world_of(&gas_scene::<2>(300, 0.4, seed));
        let all = all_pairs_next_event(&w).unwrap();
        let mut t = SweptTree::default();
        t.build(&w, 0.0, all.time);
        let found = t.earliest_body_event(&w);
        if all.kind == EventKind::Body {
            assert_eq!(found.best, Some(all));
        }
        assert!(
            found.narrow_calls < 300 * 299 / 2 / 10,
            "{}",
            found.narrow_calls
        );
        // A horizon just short of the earliest body event finds nothing earlier.
        let body_min = (0..300)
            .flat_map(|i| (i + 1..300).map(move |j| (i, j)))
            .filter_map(|(i, j)| {
                crate::contact::narrow::toi_circle_circle(
                    &w.motion(i),
                    w.radius(i),
                    &w.motion(j),
                    w.radius(j),
                )
            })
            .fold(f64::INFINITY, f64::min);
        t.build(&w, 0.0, body_min * (1.0 - 1e-12));
        assert_eq!(t.earliest_body_event(&w).best, None);
    }
}

#[test]
fn options_are_validated() {
    let ok = FinderOptions::default();
    assert!(BvhFinder::<2>::new(&ok).is_ok());
    let cases = [
        (
            "bvh_grow",
            FinderOptions {
                bvh_grow: 1.0,
                ..ok.clone()
            },
        ),
        (
            "bvh_grow",
            FinderOptions {
                bvh_grow: f64::INFINITY,
                ..ok.clone()
            },
        ),
        (
            "bvh_grow",
            FinderOptions {
                bvh_grow: f64::NAN,
                ..ok.clone()
            },
        ),
        (
            "bvh_shrink",
            FinderOptions {
                bvh_shrink: 0.0,
                ..ok.clone()
            },
        ),
        (
            "bvh_shrink",
            FinderOptions {
                bvh_shrink: 1.5,
                ..ok.clone()
            },
        ),
        (
            "bvh_initial_dt",
            FinderOptions {
                bvh_initial_dt: 0.0,
                ..ok.clone()
            },
        ),
        (
            "bvh_initial_dt",
            FinderOptions {
                bvh_initial_dt: -1.0,
                ..ok.clone()
            },
        ),
    ];
    for (name, options) in cases {
        match make_finder::<3>("bvh", &options) {
            Err(FinderError::Option { option, .. }) => assert_eq!(option, name),
            other => panic!("{name}: {:?}", other.map(|f| f.name())),
        }
    }
    // Shrink 1 (never shrink) is allowed.
    assert!(BvhFinder::<2>::new(&FinderOptions {
        bvh_shrink: 1.0,
        ..ok
    })
    .is_ok());
}

/// Drives `world` with the finder, checking the event against the oracle and the tree with
/// `validate` after every query.
fn run_validated<const D: usize>(
    scene: &Scene<D>,
    options: &FinderOptions,
    events: usize,
) -> BvhFinder<D> {
    let mut world = world_of(scene);
    let mut f = BvhFinder::new(options).unwrap();
    f.init(&world).unwrap();
    for _ in 0..events {
        let e = f.next_event(&world);
        assert_eq!(e, all_pairs_next_event(&world));
        f.validate(&world).unwrap();
        let Some(e) = e else { break };
        resolve(&mut world, e);
        let changed: &[usize] = match e.kind {
            EventKind::Body => &[e.a as usize, e.b as usize],
            EventKind::Wall | EventKind::Reset | EventKind::Edit => &[e.a as usize],
        };
        f.update(&world, changed);
    }
    f
}

#[test]
fn tree_stays_valid_through_runs() {
    for &seed in &SEEDS {
        let f = run_validated(
            &gas_scene::<2>(120, 0.35, seed),
            &FinderOptions::default(),
            400,
        );
        assert!(f.stats().refits > 0 && f.stats().builds > 300);
        run_validated(
            &gas_scene::<3>(80, 0.2, seed),
            &FinderOptions::default(),
            300,
        );
    }
}

#[test]
fn delta_adapts_and_never_vanishes() {
    let options = FinderOptions {
        bvh_initial_dt: 1.0,
        ..FinderOptions::default()
    };
    // Two bodies meeting at t = 4: Δ grows 1 → 2 → 4, then halves after the event.
    let scene = Scene::<2> {
        bodies: vec![
            BodySpec::new(Vector([0.0, 0.0]), Vector([1.0, 0.0]), 0.5),
            BodySpec::new(Vector([9.0, 0.0]), Vector([-1.0, 0.0]), 0.5),
        ],
        ..Scene::default()
    };
    let world = world_of(&scene);
    let mut f = BvhFinder::new(&options).unwrap();
    f.init(&world).unwrap();
    assert_eq!(f.next_event(&world), Some(Event::body(4.0, 0, 1)));
    assert_eq!(f.delta(), 2.0);
    assert_eq!(f.stats().refits, 2);

    // Many simultaneous events found at once keep halving Δ, down to the floor only.
    let f = run_validated(&crate::generate::rack(&Default::default()), &options, 3000);
    assert!(f.delta() >= options.bvh_initial_dt * MIN_DT_FRACTION);
}

#[test]
fn terminates_when_nothing_will_happen() {
    // Flying apart in the open: found by one exhaustive check, then cached.
    let apart = Scene::<3> {
        bodies: vec![
            BodySpec::new(Vector([0.0, 0.0, 0.0]), Vector([-1.0, 0.0, 0.0]), 0.5),
            BodySpec::new(Vector([3.0, 0.0, 0.0]), Vector([1.0, 0.0, 0.0]), 0.5),
            BodySpec::new(Vector([0.0, 3.0, 0.0]), Vector([0.0, 1e-9, 0.0]), 0.5),
        ],
        ..Scene::default()
    };
    let world = world_of(&apart);
    let mut f = BvhFinder::new(&FinderOptions::default()).unwrap();
    f.init(&world).unwrap();
    assert_eq!(f.next_event(&world), None);
    assert_eq!(f.stats().exhaustive, 1);
    assert_eq!(f.next_event(&world), None);
    assert_eq!(f.stats().searches, 1);

    // Everything at rest in a box: no tree, no search beyond the wall cache.
    let rest = gas_scene::<2>(50, 0.3, SEEDS[1]);
    let rest = Scene {
        bodies: rest
            .bodies
            .into_iter()
            .map(|b| BodySpec {
                vel: Vector::ZERO,
                ..b
            })
            .collect(),
        ..rest
    };
    let world = world_of(&rest);
    let mut f = BvhFinder::new(&FinderOptions::default()).unwrap();
    f.init(&world).unwrap();
    assert_eq!(f.next_event(&world), None);
    assert_eq!(f.stats().builds, 0);
}

/// A random world on a jittered grid (so bodies never overlap), first run for a few events
/// with the oracle so that the bodies' reference times differ, and a random horizon length.
fn arb_world<const D: usize>() -> impl Strategy<Value = (Scene<D>, usize, f64)> {
    let body = (
        prop::array::uniform::<_, D>(-0.4..0.4f64),
        prop::array::uniform::<_, D>(-5.0..5.0f64),
        0.05..1.0f64,
    );
    (
        prop::collection::vec(body, 1..120),
        0..30usize,
        1e-6..100.0f64,
    )
        .prop_map(|(bodies, events, span)| {
            let n = bodies.len();
            let base = (n as f64).powf(1.0 / D as f64).ceil() as usize + 1;
            let bodies = bodies
                .into_iter()
                .enumerate()
                .map(|(i, (jitter, v, r))| {
                    let mut p = Vector(jitter);
                    let mut cell = i;
                    for k in 0..D {
                        p[k] += 3.0 * (cell % base) as f64;
                        cell /= base;
                    }
                    BodySpec::new(p, Vector(v), r)
                })
                .collect();
            let scene = Scene {
                bodies,
                ..Scene::default()
            };
            (scene, events, span)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn validate_holds_after_builds_and_refits_2d((scene, events, span) in arb_world::<2>()) {
        check_build_refit(&scene, events, span)?;
    }

    #[test]
    fn validate_holds_after_builds_and_refits_3d((scene, events, span) in arb_world::<3>()) {
        check_build_refit(&scene, events, span)?;
    }
}

fn check_build_refit<const D: usize>(
    scene: &Scene<D>,
    events: usize,
    span: f64,
) -> Result<(), TestCaseError> {
    let mut world = world_of(scene);
    for _ in 0..events {
        let Some(e) = all_pairs_next_event(&world) else {
            break;
        };
        resolve(&mut world, e);
    }
    let now = world.now();
    let mut t = SweptTree::default();
    t.build(&world, now, now + span);
    prop_assert_eq!(t.validate(&world), Ok(()));
    for grow in [2.0, 7.5] {
        t.refit(&world, now + (t.horizon - now) * grow);
        prop_assert_eq!(t.validate(&world), Ok(()));
    }
    // Traversal agrees with a brute-force scan of the pairs within the horizon.
    let mut best = None;
    for i in 0..world.len() {
        for j in i + 1..world.len() {
            let toi = crate::contact::narrow::toi_circle_circle(
                &world.motion(i),
                world.radius(i),
                &world.motion(j),
                world.radius(j),
            );
            if let Some(tt) = toi.filter(|&tt| tt <= t.horizon) {
                best = Event::earliest(best, Some(Event::body(tt, i, j)));
            }
        }
    }
    prop_assert_eq!(t.earliest_body_event(&world).best, best);
    Ok(())
}

/// Two motions that touch at time `contact` (in exact arithmetic) with contact normal
/// `normal`, and relative velocity `tangent·slide − normal·approach` at contact.
#[allow(clippy::too_many_arguments)]
fn colliding_pair<const D: usize>(
    pa: [f64; D],
    va: [f64; D],
    (ta, tb): (f64, f64),
    (ra, rb): (f64, f64),
    normal: [f64; D],
    tangent: [f64; D],
    (slide, approach): (f64, f64),
    dt: f64,
) -> Option<(Motion<D>, Motion<D>)> {
    let mut n = Vector(normal);
    if n.norm() < 1e-3 {
        return None;
    }
    n = n * (1.0 / n.norm());
    let mut u = Vector(tangent);
    u = u - n * u.dot(n);
    if u.norm() < 1e-3 {
        return None;
    }
    u = u * (1.0 / u.norm());
    let a = Motion {
        pos: Vector(pa),
        vel: Vector(va),
        time: ta,
    };
    let contact = ta.max(tb) + dt;
    let vb = a.vel + u * slide - n * approach;
    let pb_contact = a.at(contact) + n * (ra + rb);
    let b = Motion {
        pos: pb_contact - vb * (contact - tb),
        vel: vb,
        time: tb,
    };
    Some((a, b))
}

fn check_pair_boxes<const D: usize>(
    a: Motion<D>,
    b: Motion<D>,
    ra: f64,
    rb: f64,
) -> Result<(), TestCaseError> {
    let Some(toi) = crate::contact::narrow::toi_circle_circle(&a, ra, &b, rb) else {
        return Ok(()); // a grazing pass that rounding turned into a miss: nothing to find
    };
    let t0 = a.time.max(b.time);
    // The worst cases: the swept interval ends exactly at the computed time of impact, and
    // even starts there (the boxes are then the balls at that instant, padded).
    for now in [t0, toi] {
        let (ba, bb) = (
            swept_box(&a, ra, now, toi, None),
            swept_box(&b, rb, now, toi, None),
        );
        prop_assert!(
            ba.overlaps(&bb),
            "now = {now}, toi = {toi}: {ba:?} vs {bb:?}"
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// The padding claim of the module docs: whatever the scale of coordinates and times,
    /// and however grazing the contact, the swept boxes of a pair overlap at its computed
    /// time of impact. (Without the padding, about a third of the axis-aligned cases fail.)
    #[test]
    fn swept_boxes_overlap_at_the_time_of_impact(
        pa in prop::array::uniform::<_, 3>(-1.0..1.0f64),
        va in prop::array::uniform::<_, 3>(-1.0..1.0f64),
        times in (-1.0..1.0f64, -1.0..1.0f64),
        radii in (0.01..1.0f64, 0.01..1.0f64),
        normal in prop::array::uniform::<_, 3>(-1.0..1.0f64),
        tangent in prop::array::uniform::<_, 3>(-1.0..1.0f64),
        slide in 0.0..10.0f64,
        approach_exp in -12.0..1.0f64,
        dt in 0.0..100.0f64,
        space_exp in -2i32..7,
        time_exp in -2i32..7,
        two_d in any::<bool>(),
        aligned in prop::option::of(0usize..2),
    ) {
        // Contact normals along an axis are where the boxes are tightest (the balls' gap
        // along the axis is their full distance), so rounding would separate them.
        let normal = match aligned {
            Some(k) => {
                let mut e = [0.0; 3];
                e[k] = if slide > 5.0 { 1.0 } else { -1.0 };
                e
            }
            None => normal,
        };
        let (ls, lt) = (10f64.powi(space_exp), 10f64.powi(time_exp));
        let scale = |p: [f64; 3], s: f64| p.map(|x| x * s);
        let times = (times.0 * lt, times.1 * lt);
        let approach = 10f64.powf(approach_exp);
        if two_d {
            let d2 = |p: [f64; 3]| [p[0], p[1]];
            if let Some((a, b)) = colliding_pair::<2>(
                d2(scale(pa, ls)), d2(va), times, radii, d2(normal), d2(tangent),
                (slide, approach), dt,
            ) {
                check_pair_boxes(a, b, radii.0, radii.1)?;
            }
        } else if let Some((a, b)) = colliding_pair::<3>(
            scale(pa, ls), va, times, radii, normal, tangent, (slide, approach), dt,
        ) {
            check_pair_boxes(a, b, radii.0, radii.1)?;
        }
    }
}

#[test]
fn half_image_shifts_and_their_negations_are_every_non_zero_shift() {
    fn check<const D: usize>(size: Vector<D>) {
        let mut half = Vec::new();
        super::tree::half_image_shifts(&size, &mut half);
        assert_eq!(half.len(), (3usize.pow(D as u32) - 1) / 2);
        let mut all: Vec<Vector<D>> = half.iter().flat_map(|&s| [s, Vector::ZERO - s]).collect();
        all.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap());
        all.dedup();
        assert_eq!(all.len(), 3usize.pow(D as u32) - 1, "{all:?}");
        for s in &all {
            assert!(s.0.iter().any(|&x| x != 0.0));
            for d in 0..D {
                assert!([-size[d], 0.0, size[d]].contains(&s[d]), "{s:?}");
            }
        }
    }
    check(Vector([3.0, 5.0]));
    check(Vector([3.0, 5.0, 7.0]));
}

/// Two bodies that meet only across the faces of a periodic box (through the image that
/// shifts both axes): the traversal finds their time through the images, the oracle's.
#[test]
fn periodic_pairs_are_found_through_the_images() {
    let scene = Scene::<2> {
        bodies: vec![
            BodySpec::new(Vector([0.6, 0.7]), Vector([-1.0, -1.0]), 0.5),
            BodySpec::new(Vector([9.3, 9.4]), Vector([1.0, 1.0]), 0.5),
            BodySpec::new(Vector([5.0, 5.0]), Vector([0.0, 0.0]), 0.5),
        ],
        periodic: Some(Vector([10.0, 10.0])),
        ..Scene::default()
    };
    let world = world_of(&scene);
    let size = world.periodic().unwrap();
    let want = crate::contact::periodic::toi_circle_circle_periodic(
        &world.motion(0),
        0.5,
        &world.motion(1),
        0.5,
        &size,
    )
    .expect("they meet across the corner");
    assert!(want > 0.0);
    let mut t = SweptTree::default();
    t.build(&world, 0.0, 1.0);
    assert_eq!(t.shifts.len(), 4);
    let found = t
        .earliest_body_event(&world)
        .best
        .expect("found through an image");
    assert_eq!(
        (found.a, found.b, found.time.to_bits()),
        (0, 1, want.to_bits())
    );
    // Without the image checks the pair's boxes are apart: nothing is found.
    t.shifts.clear();
    assert_eq!(t.earliest_body_event(&world).best, None);
    // The whole finder, box exits included, agrees with the oracle.
    let mut f = BvhFinder::<2>::new(&FinderOptions::default()).unwrap();
    f.init(&world).unwrap();
    assert_eq!(f.next_event(&world), all_pairs_next_event(&world));
}
