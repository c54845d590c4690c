//! Where each luminaire's flux goes: what its file states, what its candela table carries,
//! and how much of it reaches the room's surfaces directly; the rest leaves through openings
//! (or is the integration's error in a closed room).

use serde::Serialize;

use crate::scene::Luminaire;

/// Relative disagreement between the flux a photometric file states and the flux its candela
/// table integrates to above which the build warns: a well-formed file agrees to its
/// rounding, far better than this.
pub const FLUX_AGREEMENT: f64 = 0.005;

/// One luminaire's flux, lm.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LuminaireFlux {
    /// The luminaire's name in the scene.
    pub name: String,
    /// Its photometric file.
    pub file: String,
    /// The luminaire's flux as the file states it (EULUMDAT: lamp flux × LORL), lm; `None`
    /// when the file states none (LM-63).
    pub stated: Option<f64>,
    /// The rated flux of its lamps, lm, if the file gives one.
    pub lamps: Option<f64>,
    /// The integral of its candela table over the sphere, lm: the file's own, as measured
    /// (no tilt or maintenance factor), which is what `stated` and `lamps` are checked against.
    pub integrated: f64,
    /// Its tilt table's factor at its orientation (dimensionless; 1 without a table).
    pub tilt_factor: f64,
    /// What it emits in the scene: `integrated` times its tilt and maintenance factors, lm.
    pub emitted: f64,
    /// What reaches the scene's patches directly, `Σ A_i E_i`, lm.
    pub received: f64,
    /// `emitted − received`, lm: light leaving through openings (and, in a closed room, the
    /// integration's error).
    pub escaping: f64,
    /// Why the file looks wrong, if it does.
    pub warning: Option<String>,
}

impl LuminaireFlux {
    /// The account of `luminaire`, whose direct light puts `received` lm on the patches.
    pub fn new(luminaire: &Luminaire, received: f64) -> LuminaireFlux {
        let photometry = &luminaire.photometry;
        let integrated = photometry.flux();
        let emitted = integrated * luminaire.tilt_factor * luminaire.maintenance_factor;
        let file = luminaire.file.display().to_string();
        let apart = |a: f64, b: f64| (a - b).abs() / b.abs().max(f64::MIN_POSITIVE);
        let warning = match (photometry.luminaire_flux, photometry.lamp_flux) {
            (Some(stated), _) if apart(integrated, stated) > FLUX_AGREEMENT => Some(format!(
                "{file}: the candela table integrates to {integrated:.1} lm, the file states \
                 {stated:.1} lm ({:.1} % apart)",
                100.0 * apart(integrated, stated)
            )),
            (None, Some(lamps)) if integrated > lamps * (1.0 + FLUX_AGREEMENT) => Some(format!(
                "{file}: the candela table integrates to {integrated:.1} lm, more than the \
                 {lamps:.1} lm of its lamps"
            )),
            _ => None,
        };
        LuminaireFlux {
            name: luminaire.name.clone(),
            file,
            stated: photometry.luminaire_flux,
            lamps: photometry.lamp_flux,
            integrated,
            tilt_factor: luminaire.tilt_factor,
            emitted,
            received,
            escaping: emitted - received,
            warning,
        }
    }
}
