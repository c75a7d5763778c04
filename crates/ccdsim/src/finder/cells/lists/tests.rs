//! Unit tests of the list mode's structures: entries, list blocks, shells, rebuild cells.

use super::*;
use proptest::prelude::*;

fn motion(pos: [f64; 2], vel: [f64; 2], time: f64) -> Motion<2> {
    Motion {
        pos: Vector(pos),
        vel: Vector(vel),
        time,
    }
}

#[test]
fn shell_exit_times() {
    // From the centre at unit speed: h later.
    let m = motion([1.0, 2.0], [0.0, -1.0], 3.0);
    assert_eq!(shell_exit_time(&m, &Vector([1.0, 2.0]), 0.25, 3.0), 3.25);
    // Referenced later on the same path: the same exit.
    let t = shell_exit_time(&m, &Vector([1.0, 2.0]), 0.25, 3.1);
    assert!((t - 3.25).abs() < 1e-12, "{t}");
    // Entering from behind the shell's far side: the later root.
    let m = motion([0.0, 0.0], [2.0, 0.0], 0.0);
    let t = shell_exit_time(&m, &Vector([1.0, 0.0]), 0.5, 0.5);
    assert!((t - 0.75).abs() < 1e-12, "{t}");
    // At rest: never.
    let m = motion([0.0, 0.0], [0.0, 0.0], 0.0);
    assert_eq!(
        shell_exit_time(&m, &Vector([0.1, 0.0]), 0.5, 0.0),
        f64::INFINITY
    );
    // Outside and moving away: at once (or earlier).
    let m = motion([2.0, 0.0], [1.0, 0.0], 0.0);
    assert!(shell_exit_time(&m, &Vector([0.0, 0.0]), 0.5, 0.0) <= 0.0);
    // Far along a long flight (no cancellation): h / |v| after the reference point.
    let m = motion([0.0, 0.0], [3.0, 4.0], 0.0);
    let c = m.at(1e6);
    let t = shell_exit_time(&m, &c, 0.05, 1e6);
    assert!((t - (1e6 + 0.01)).abs() < 1e-8, "{t}");
}

#[test]
fn entries_and_images() {
    let e = entry(123_456, 26);
    assert_eq!((entry_body(e), entry_image(e)), (123_456, 26));
    assert_eq!(opposite::<2>(0), 8);
    assert_eq!(opposite::<2>(4), 4);
    assert_eq!(opposite::<3>(13), 13);
    assert_eq!(opposite::<3>(1), 25);
    let mut lists = Lists::<2>::new(3, 0.1, 1.1, 1);
    for j in 0..20 {
        lists.push(1, entry(j, 4));
    }
    assert_eq!(lists.list(1).len(), 20);
    assert!(lists.capacity() >= 20);
    for j in 0..30 {
        lists.push(2, entry(j, 3));
    }
    let sorted = |part: &[u32]| {
        let mut v = part.to_vec();
        v.sort_unstable();
        v
    };
    let (above, below) = lists.parts(2);
    let want_above: Vec<u32> = (3..30).map(|j| entry(j, 3)).collect();
    let want_below: Vec<u32> = (0..3).map(|j| entry(j, 3)).collect();
    assert_eq!(
        (sorted(above), sorted(below)),
        (want_above.clone(), want_below.clone())
    );
    assert_eq!(lists.list(1).len(), 20);
    assert!(lists.list(1).iter().all(|&e| entry_image(e) == 4));
    lists.remove(1, entry(5, 4));
    assert_eq!(lists.list(1).len(), 19);
    assert!(!lists.list(1).contains(&entry(5, 4)));
    assert!(lists.list(0).is_empty());
    let (above, below) = lists.parts(2);
    assert_eq!((sorted(above), sorted(below)), (want_above, want_below));
}

#[test]
fn lists_keep_higher_partners_first() {
    let mut lists = Lists::<3>::new(40, 0.1, 1.1, 1);
    lists.set(
        10,
        &[entry(30, 1), entry(12, 0), entry(31, 26)],
        &[entry(3, 13), entry(7, 13)],
    );
    let mut sorted = Vec::new();
    lists.sorted_list(10, &mut sorted);
    let want = [
        entry(3, 13),
        entry(7, 13),
        entry(12, 0),
        entry(30, 1),
        entry(31, 26),
    ];
    assert_eq!(sorted, want);
    assert_eq!(
        lists.parts(10),
        (
            &[entry(30, 1), entry(12, 0), entry(31, 26)][..],
            &[entry(3, 13), entry(7, 13)][..]
        )
    );
    lists.remove(10, entry(30, 1));
    assert_eq!(
        lists.parts(10),
        (
            &[entry(31, 26), entry(12, 0)][..],
            &[entry(7, 13), entry(3, 13)][..]
        )
    );
    lists.remove(10, entry(7, 13));
    lists.push(10, entry(5, 4));
    lists.push(10, entry(20, 4));
    assert_eq!(
        lists.parts(10),
        (
            &[entry(31, 26), entry(12, 0), entry(20, 4)][..],
            &[entry(5, 4), entry(3, 13)][..]
        )
    );
    // Growing the layout keeps every block, headers included.
    for j in 0..40 {
        if j != 10 {
            lists.push(11, entry(j, 2));
        }
    }
    assert_eq!(lists.list(11).len(), 39);
    assert_eq!(lists.parts(11).0.len(), 28);
    assert_eq!(
        lists.parts(10),
        (
            &[entry(31, 26), entry(12, 0), entry(20, 4)][..],
            &[entry(5, 4), entry(3, 13)][..]
        )
    );
}

#[test]
fn overlap_is_symmetric() {
    let mut lists = Lists::<2>::new(2, 0.1, 1.1, 1);
    let shift = Vector([-10.0, 0.0]);
    let mirrored = Vector::ZERO - shift;
    for (x0, x1, want) in [
        ([0.1, 0.3], [9.35, 0.7], true),
        ([0.1, 0.3], [9.0, 0.7], false),
        ([0.1 + 1e-17, 0.3], [9.2 + 0.1 * 3.0, 0.3], true),
    ] {
        lists.centre[0] = Vector(x0);
        lists.centre[1] = Vector(x1);
        let a = lists.overlap(&lists.centre[0], &lists.centre[1], &shift);
        let b = lists.overlap(&lists.centre[1], &lists.centre[0], &mirrored);
        assert_eq!((a, b), (want, want), "{x0:?} {x1:?}");
    }
}

/// The cells a rebuild tests around a point `x` of a periodic box `period` (cells at
/// least `cut (1 + MARGIN)` wide): for every point `y` of the box and every image shift,
/// if the image of `y` is within `cut` of `x`, the cell of `y` is tested with that image;
/// and every tested cell is one of the 3^D block, once.
fn check_near_cells(period: [f64; 3], cut: f64, x: [f64; 3], ys: &[[f64; 3]]) {
    let grid = Grid::<3>::new(
        ys.len(),
        cut * (1.0 + MARGIN),
        Vector::ZERO,
        Vector::ZERO,
        Some(Vector(period)),
    );
    let lists = Lists::<3>::new(1, 0.1, cut, 1);
    let x = Vector(x);
    let k = grid.coords_of_point(&x).map(|c| c as u32);
    let mut cells = [(0u32, 0u8); 27];
    let count = lists.near_cells(&grid, &k, &x, &mut cells);
    let near = &cells[..count];
    let mut block = Vec::new();
    grid.visit_neighbours(&k, |c, _, image| block.push((c, image)));
    for (a, cell) in near.iter().enumerate() {
        assert!(block.contains(cell), "{cell:?} is not a neighbour");
        assert!(!near[..a].contains(cell), "{cell:?} twice");
    }
    for y in ys {
        let y = Vector(*y);
        let c = grid.linear(&grid.coords_of_point(&y));
        for image in 0..27u8 {
            if lists.overlap(&x, &y, &grid.shift_of(image)) {
                assert!(
                    near.contains(&(c, image)),
                    "{y:?} (cell {c}, image {image}) within reach of {x:?} is skipped"
                );
            }
        }
    }
}

#[test]
fn near_cells_on_faces_and_corners() {
    // Points on cell faces and box faces, a box of a single cell along z.
    let (period, cut) = ([6.0, 4.5, 2.0], 1.4);
    let w = 6.0 / 4.0;
    let mut ys = Vec::new();
    for a in 0..=8 {
        for b in 0..=6 {
            for c in 0..=4 {
                let p = [f64::from(a) * 0.75, f64::from(b) * 0.75, f64::from(c) * 0.5];
                ys.push(p.map(|v| v.min(6.0 - 1e-12)));
            }
        }
    }
    for x in [
        [w, 1.5, 0.0],
        [0.0, 0.0, 0.0],
        [5.999, 4.4999, 1.9999],
        [2.2, 2.2, 1.0],
    ] {
        check_near_cells(period, cut, x, &ys);
    }
}

proptest! {
    /// A rebuild skips no cell holding a body within reach (see `near_cells`).
    #[test]
    fn near_cells_skip_only_far_cells(
        sides in proptest::array::uniform3(2.0f64..12.0),
        cut in 0.5f64..2.0,
        x in proptest::array::uniform3(0.0f64..1.0),
        ys in proptest::collection::vec(proptest::array::uniform3(0.0f64..1.0), 1..200),
    ) {
        let scale = |u: [f64; 3]| std::array::from_fn(|d| u[d] * sides[d]);
        let ys: Vec<[f64; 3]> = ys.into_iter().map(scale).collect();
        check_near_cells(sides, cut, scale(x), &ys);
    }

    /// Up to its exit time, a body stays within the shell (up to rounding), and at the
    /// exit it is on the shell's surface.
    #[test]
    fn bodies_stay_in_their_shell_until_the_exit(
        px in -50.0f64..50.0, py in -50.0f64..50.0,
        vx in -5.0f64..5.0, vy in -5.0f64..5.0,
        h in 0.001f64..1.0, t0 in -10.0f64..100.0, lead in 0.0f64..3.0,
        frac in 0.0f64..1.0, u in 0.0f64..1.0,
    ) {
        let m = motion([px, py], [vx, vy], t0);
        prop_assume!(vx * vx + vy * vy > 1e-6);
        // A centre the body passes at t0 + lead, moved off its path by up to h·frac.
        let tc = t0 + lead;
        let off = Vector([-vy, vx]) * (h * frac / (vx * vx + vy * vy).sqrt());
        let centre = m.at(tc) + off;
        // Reference time: the body is inside the shell then.
        let t_ref = tc;
        let exit = shell_exit_time(&m, &centre, h, t_ref);
        prop_assert!(exit >= t_ref);
        let tol = 1e-9 * (1.0 + m.at(exit).norm());
        for k in 0..=16 {
            let t = t_ref + (exit - t_ref) * f64::from(k) / 16.0;
            prop_assert!((m.at(t) - centre).norm() <= h + tol);
        }
        let t = t_ref + (exit - t_ref) * u;
        prop_assert!((m.at(t) - centre).norm() <= h + tol);
        prop_assert!(((m.at(exit) - centre).norm() - h).abs() <= tol);
    }
}
