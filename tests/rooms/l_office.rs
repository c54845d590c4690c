//! The L-shaped office of `examples/l-office/`: closed, and its work-plane grid has no point
//! in the notch, in a column, or within the margin of a wall.

use super::*;

/// The example's scene.
fn l_office() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/l-office/scene.toml");
    load(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_l_office_grid_covers_the_l_only() {
    let scene = l_office();
    let zone = scene
        .zones
        .iter()
        .find(|z| z.name == "work_plane")
        .expect("work plane");
    let grid = zone.grid.as_ref().expect("grid");
    let margin = 0.5;
    // The room's walls as the example writes them, and the columns, by hand.
    let l = [
        [0.0, 0.0],
        [12.0, 0.0],
        [12.0, 4.0],
        [7.0, 4.0],
        [7.0, 8.0],
        [0.0, 8.0],
    ];
    let inside_l = |x: f64, y: f64| {
        (0.0..=12.0).contains(&x) && (0.0..=8.0).contains(&y) && (x <= 7.0 || y <= 4.0)
    };
    let to_walls = |x: f64, y: f64| {
        (0..6)
            .map(|k| {
                let (a, b): ([f64; 2], [f64; 2]) = (l[k], l[(k + 1) % 6]);
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let t = (((x - a[0]) * dx + (y - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
                (x - a[0] - t * dx).hypot(y - a[1] - t * dy)
            })
            .fold(f64::INFINITY, f64::min)
    };
    let on_plane = |x: f64, y: f64| inside_l(x, y) && to_walls(x, y) >= margin;
    let columns = [([3.3, 3.8], [3.7, 4.2]), ([8.8, 1.8], [9.2, 2.2])];
    let in_column = |x: f64, y: f64| {
        columns
            .iter()
            .any(|(lo, hi)| x > lo[0] && x < hi[0] && y > lo[1] && y < hi[1])
    };
    let mut points = 0;
    for (p, normal) in grid.points() {
        points += 1;
        assert!(normal.z == 1.0, "the plane faces up");
        assert!((p.z - 0.8).abs() < 1e-12);
        assert!(!(p.x > 7.0 && p.y > 4.0), "{p:?} in the notch");
        assert!(
            on_plane(p.x, p.y),
            "{p:?} outside the L or within its margin"
        );
        assert!(!in_column(p.x, p.y), "{p:?} in a column");
    }
    // Independently: the lattice the grid was cut from (cells over the bounding box less the
    // margin), its centres sorted by hand against the L, its margin and the columns.
    let [piece] = &grid.pieces[..] else {
        panic!("one piece expected, {}", grid.pieces.len())
    };
    let (mut kept, mut obstructed) = (0, 0);
    for j in 0..piece.counts[1] {
        for i in 0..piece.counts[0] {
            let x = margin + (i as f64 + 0.5) * piece.cell[0];
            let y = margin + (j as f64 + 0.5) * piece.cell[1];
            match (on_plane(x, y), in_column(x, y)) {
                (true, false) => kept += 1,
                (true, true) => obstructed += 1,
                _ => {}
            }
        }
    }
    println!(
        "l-office work plane: {points} points of a {} × {} lattice, {} left out in columns",
        piece.counts[0], piece.counts[1], grid.obstructed
    );
    assert_eq!(points, kept);
    assert_eq!(grid.obstructed, obstructed);
    assert!(grid.obstructed > 0, "the columns stand in the grid");
    // The receivers cover the L less its margin band. Offset inwards by m, the L's edges give
    // the mitred L of area A − P m + m² (convex corners − reflex corners) = 76 − 40 m + 4 m²,
    // which leaves out the square of side m by the reflex corner (7, 4); of that square, the
    // points farther than m from the corner are in the band's complement: m² − π m²/4 more.
    let ZoneKind::WorkPlane { receivers, .. } = &zone.kind else {
        panic!("a work plane")
    };
    let area: f64 = receivers.iter().map(|r| r.area).sum();
    let m2 = margin * margin;
    let want = 76.0 - 40.0 * margin + 4.0 * m2 + (m2 - std::f64::consts::PI * m2 / 4.0);
    println!(
        "receivers: {} patches, {area:.4} m² (band rule {want:.4} m²)",
        receivers.len()
    );
    // The buffer draws the quarter circle as a polygon: within 1e-3 relative.
    assert!((area - want).abs() < 1e-3 * want, "{area} vs {want}");
}

#[test]
fn the_l_office_is_closed() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/l-office/scene.toml");
    let prepared = prepare(&path, &FormFactorOptions::default()).unwrap();
    let h = &prepared.form_factor_health;
    println!(
        "l-office: {} patches, row sums {:.6} .. {:.6}, escaping {:.2e}",
        prepared.scene.patches.len(),
        h.row_sum_min,
        h.row_sum_max,
        h.escaping
    );
    // Closed as the build report counts it (`formfactor::health::CLOSED_TOLERANCE`, 1e-2):
    // no light escapes through the walls, the windows or round the columns.
    assert!(h.closed, "row sums {} .. {}", h.row_sum_min, h.row_sum_max);
    assert!(h.escaping.abs() < 1e-4, "escaping {}", h.escaping);
    for w in &h.warnings {
        println!("warning: {w}");
    }
}
