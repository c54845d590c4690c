//! A zone's calculation grid as the commands report it: its layout, its points' readings and
//! its EN 12464-1 figures.

use serde::Serialize;

/// One point of a calculation grid.
#[derive(Clone, Debug, Serialize)]
pub struct GridPoint {
    /// Position, m.
    pub position_m: [f64; 3],
    /// Irradiance per band (W/m²) or illuminance (lux).
    pub irradiance: Vec<f64>,
}

/// One piece of a calculation grid's layout (a lattice over a rectangle of a plane).
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct PieceLayout {
    /// Cells along the piece's first and second side.
    pub counts: [usize; 2],
    /// Points the piece keeps: the cell centres on its area.
    pub points: usize,
    /// Largest spacing the layout used, m.
    pub spacing_m: f64,
    /// Cell sides, m.
    pub cell_m: [f64; 2],
    /// Band left out at the walls, m.
    pub border_m: f64,
    /// Unit normal the piece's points face.
    pub normal: [f64; 3],
}

impl From<&crate::scene::grid::GridPiece> for PieceLayout {
    fn from(g: &crate::scene::grid::GridPiece) -> Self {
        PieceLayout {
            counts: g.counts,
            points: g.points.len(),
            spacing_m: g.spacing,
            cell_m: g.cell,
            border_m: g.border,
            normal: g.normal.to_array(),
        }
    }
}

impl From<eigenrad_runtime::GridPiece> for PieceLayout {
    fn from(g: eigenrad_runtime::GridPiece) -> Self {
        let wide = f64::from;
        PieceLayout {
            counts: g.counts,
            points: g.points,
            spacing_m: wide(g.spacing),
            cell_m: g.cell.map(wide),
            border_m: wide(g.border),
            normal: g.normal.map(wide),
        }
    }
}

/// A zone's calculation grid (EN 12464-1:2021, 4.4) and its figures, per band.
#[derive(Clone, Debug, Serialize)]
pub struct GridReadout {
    /// Zone name.
    pub zone: String,
    /// The lattices the grid is made of: one for a work plane or a task area, up to four for
    /// the band around a task area, one per plane of a surface zone.
    pub pieces: Vec<PieceLayout>,
    /// `E_avg` per band: mean over the points.
    pub average: Vec<f64>,
    /// `E_min` per band.
    pub minimum: Vec<f64>,
    /// `E_max` per band.
    pub maximum: Vec<f64>,
    /// `U_o = E_min / E_avg` per band.
    pub uniformity: Vec<f64>,
    /// Every point, first side fastest.
    pub points: Vec<GridPoint>,
    /// Cell centres left out because they lie inside an obstacle (known from the scene; 0
    /// when read from a basis alone).
    pub obstructed: usize,
}

impl GridReadout {
    /// A grid's readout from its layout and its points' readings (`values[point][band]`).
    /// The figures are [`eigenrad_runtime::Figures`], the one definition: `figures` as the
    /// runtime read them (per band), or, when `None`, taken here of `values` in `f64`.
    pub fn new(
        zone: String,
        pieces: Vec<PieceLayout>,
        positions: Vec<[f64; 3]>,
        values: &[Vec<f64>],
        figures: Option<&[eigenrad_runtime::Figures]>,
    ) -> GridReadout {
        let bands = values.first().map_or(0, Vec::len);
        let figures: Vec<Option<eigenrad_runtime::Figures<f64>>> = match figures {
            Some(read) => read
                .iter()
                .map(|f| {
                    Some(eigenrad_runtime::Figures {
                        average: f64::from(f.average),
                        minimum: f64::from(f.minimum),
                        maximum: f64::from(f.maximum),
                        uniformity: f64::from(f.uniformity),
                        points: f.points,
                    })
                })
                .collect(),
            None => (0..bands)
                .map(|b| eigenrad_runtime::Figures::of(values.iter().map(|v| v[b])))
                .collect(),
        };
        let pick = |f: fn(&eigenrad_runtime::Figures<f64>) -> f64| {
            figures
                .iter()
                .map(|x| x.as_ref().map_or(f64::NAN, f))
                .collect()
        };
        GridReadout {
            zone,
            pieces,
            average: pick(|f| f.average),
            minimum: pick(|f| f.minimum),
            maximum: pick(|f| f.maximum),
            uniformity: pick(|f| f.uniformity),
            points: positions
                .into_iter()
                .zip(values)
                .map(|(position_m, v)| GridPoint {
                    position_m,
                    irradiance: v.clone(),
                })
                .collect(),
            obstructed: 0,
        }
    }
}

/// The grids of `scene`'s zones from the model's outputs (`outputs[o][band]`: sensors, zones,
/// then grid points).
pub fn scene_grids(scene: &crate::scene::Scene, outputs: &[Vec<f64>]) -> Vec<GridReadout> {
    let mut next = crate::formfactor::outputs::grid_offset(scene);
    let mut grids = Vec::new();
    for z in &scene.zones {
        let Some(g) = &z.grid else { continue };
        let values = &outputs[next..next + g.len()];
        next += g.len();
        let mut readout = GridReadout::new(
            z.name.clone(),
            g.pieces.iter().map(PieceLayout::from).collect(),
            g.points().map(|(p, _)| p.to_array()).collect(),
            values,
            None,
        );
        readout.obstructed = g.obstructed;
        grids.push(readout);
    }
    grids
}
