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
    /// The integral of its candela table over the sphere, lm.
    pub integrated: f64,
    /// What it emits in the scene: `integrated` times its maintenance factor, lm.
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
        let emitted = integrated * luminaire.maintenance_factor;
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
        // The lamp-tilt factors are read but not applied: say so where they matter.
        let tilted = photometry
            .tilt
            .as_ref()
            .is_some_and(|t| t.factors.iter().any(|&f| (f - 1.0).abs() > FLUX_AGREEMENT));
        let tilt = tilted.then(|| {
            format!(
                "{file}: its tilt table (TILT=INCLUDE) is not applied; the distribution is \
                 used as measured, whatever the luminaire's aim"
            )
        });
        let warning = match (warning, tilt) {
            (Some(a), Some(b)) => Some(format!("{a}; {b}")),
            (a, b) => a.or(b),
        };
        LuminaireFlux {
            name: luminaire.name.clone(),
            file,
            stated: photometry.luminaire_flux,
            lamps: photometry.lamp_flux,
            integrated,
            emitted,
            received,
            escaping: emitted - received,
            warning,
        }
    }
}
