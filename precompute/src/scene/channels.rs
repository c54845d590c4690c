//! Channels: which surfaces each drives and how much they emit at level 1. A channel may
//! drive luminaires only (`[[luminaire]]` entries naming it), and then no surface.

use toml::Spanned;

use eigenrad_runtime::MAX_EXITANCE;

use super::context::{resolve_surfaces, unique, Ctx, RawSurface};
use super::error::SceneError;
use super::file::ChannelDef;
use super::{Channel, Surface};
use crate::geometry::Patch;

/// The channels, and per surface the channel driving it and its exitance at level 1.
pub(crate) struct Emitters {
    pub channels: Vec<Channel>,
    pub channel_of_surface: Vec<Option<usize>>,
    /// Per surface and band, lux or W/m².
    pub surface_emission: Vec<Vec<f64>>,
}

/// Resolves the channels. `lit[k]` says whether a luminaire is in channel `k`;
/// `material_emission` is each surface's material emission; `raw` locates each surface's
/// material for messages.
pub(crate) fn resolve(
    ctx: &Ctx,
    defs: &[Spanned<ChannelDef>],
    lit: &[bool],
    surfaces: &[Surface],
    patches: &[Patch],
    raw: &[RawSurface],
    material_emission: &[Vec<f64>],
) -> Result<Emitters, SceneError> {
    let area_of = |i: usize| -> f64 {
        patches[surfaces[i].patch_range.clone()]
            .iter()
            .map(|p| p.area)
            .sum()
    };

    unique(
        "channel",
        defs.iter().map(|c| (c.get_ref().name.as_str(), ctx.at(c))),
    )?;
    for def in defs {
        addressable(ctx, def)?;
    }
    let mut channel_of_surface: Vec<Option<usize>> = vec![None; surfaces.len()];
    let mut surface_emission = vec![vec![0.0; ctx.bands]; surfaces.len()];
    let mut channels = Vec::with_capacity(defs.len());
    for (k, def) in defs.iter().enumerate() {
        let c = def.get_ref();
        let members = members(ctx, def, surfaces, lit[k])?;
        if members.is_empty() {
            // Luminaires only: their light is their photometry's, not a surface's exitance.
            if let Some(given) = c.exitance.as_ref().or(c.flux.as_ref()) {
                return Err(SceneError::Invalid {
                    at: ctx.at(given),
                    field: format!("channel `{}`", c.name),
                    message: "gives `exitance` or `flux` but names no surface; its luminaires' \
                              light comes from their photometric files"
                        .into(),
                });
            }
            channels.push(Channel {
                name: c.name.clone(),
                surfaces: members,
                exitance: vec![0.0; ctx.bands],
            });
            continue;
        }
        let area: f64 = members.iter().map(|&i| area_of(i)).sum();
        let exitance = exitance(ctx, c, area)?;
        for &i in &members {
            if let Some(previous) = channel_of_surface[i] {
                return Err(SceneError::Emitter {
                    at: ctx.at(def),
                    surface: surfaces[i].name.clone(),
                    message: format!(
                        "is in channel `{}` and in channel `{}`; a surface can be in one only",
                        defs.get(previous)
                            .map_or("?", |d| d.get_ref().name.as_str()),
                        c.name
                    ),
                });
            }
            channel_of_surface[i] = Some(k);
            surface_emission[i] = exitance
                .clone()
                .unwrap_or_else(|| material_emission[i].clone());
        }
        let mean: Vec<f64> = (0..ctx.bands)
            .map(|b| {
                members
                    .iter()
                    .map(|&i| surface_emission[i][b] * area_of(i))
                    .sum::<f64>()
                    / area
            })
            .collect();
        if mean.iter().all(|&x| x == 0.0) {
            return Err(SceneError::EmptyChannel {
                at: ctx.at(def),
                channel: c.name.clone(),
                message: "none of its surfaces emits: give `exitance` or `flux`, or use an \
                          emitting material"
                    .into(),
            });
        }
        channels.push(Channel {
            name: c.name.clone(),
            surfaces: members,
            exitance: mean,
        });
    }
    check_driven(surfaces, raw, &channel_of_surface, material_emission)?;
    Ok(Emitters {
        channels,
        channel_of_surface,
        surface_emission,
    })
}

/// The surfaces channel `def` drives: those it names, then those of the materials it names;
/// an error if that is none and no luminaire is in the channel (`lit`).
fn members(
    ctx: &Ctx,
    def: &Spanned<ChannelDef>,
    surfaces: &[Surface],
    lit: bool,
) -> Result<Vec<usize>, SceneError> {
    let c = def.get_ref();
    let what = format!("channel `{}`", c.name);
    let mut members = match &c.surfaces {
        Some(refs) => resolve_surfaces(ctx, surfaces, refs, &format!("{what}.surfaces"))?,
        None => Vec::new(),
    };
    if let Some(mats) = &c.materials {
        for m in mats.get_ref() {
            let found: Vec<usize> = (0..surfaces.len())
                .filter(|&i| &surfaces[i].material == m)
                .collect();
            if found.is_empty() {
                return Err(SceneError::Unknown {
                    at: ctx.at(mats),
                    field: format!("{what}.materials"),
                    kind: "material (on any surface)",
                    name: m.clone(),
                });
            }
            for i in found {
                if !members.contains(&i) {
                    members.push(i);
                }
            }
        }
    }
    if members.is_empty() && !lit {
        return Err(SceneError::EmptyChannel {
            at: ctx.at(def),
            channel: c.name.clone(),
            message: "names no surface and no luminaire is in it: give `surfaces` or \
                      `materials`, or name the channel in a [[luminaire]]"
                .into(),
        });
    }
    Ok(members)
}

/// A channel's name must be one `eigenrad eval --level NAME=VALUE` can address: not empty,
/// no `=`, no white space at either end.
fn addressable(ctx: &Ctx, def: &Spanned<ChannelDef>) -> Result<(), SceneError> {
    let name = &def.get_ref().name;
    let problem = if name.is_empty() {
        Some("is empty")
    } else if name.contains('=') {
        Some("contains `=`")
    } else if name.trim() != name {
        Some("begins or ends with white space")
    } else {
        None
    };
    match problem {
        Some(problem) => Err(SceneError::Invalid {
            at: ctx.at(def),
            field: format!("channel `{name}`.name"),
            message: format!("the name {problem}, so `--level NAME=VALUE` cannot address it"),
        }),
        None => Ok(()),
    }
}

/// The exitance channel `c` gives its surfaces at level 1 (lux or W/m² per band): as written,
/// or its flux over their `area` (m²); `None` when it leaves them their materials'.
fn exitance(ctx: &Ctx, c: &ChannelDef, area: f64) -> Result<Option<Vec<f64>>, SceneError> {
    let what = format!("channel `{}`", c.name);
    Ok(match (&c.exitance, &c.flux) {
        (Some(e), Some(_)) => {
            return Err(SceneError::Invalid {
                at: ctx.at(e),
                field: format!("{what}.exitance"),
                message: "give `exitance` or `flux`, not both".into(),
            })
        }
        (Some(e), None) => {
            let field = format!("{what}.exitance");
            Some(ctx.check_exitance(ctx.per_band(e, &field)?, &ctx.at(e), &field)?)
        }
        (None, Some(f)) => {
            let field = format!("{what}.flux");
            let flux = ctx.check_exitance(ctx.per_band(f, &field)?, &ctx.at(f), &field)?;
            let exitance: Vec<f64> = flux.iter().map(|f| f / area).collect();
            if exitance.iter().any(|e| *e > f64::from(MAX_EXITANCE)) {
                return Err(SceneError::OutOfRange {
                    at: ctx.at(f),
                    field,
                    message: format!(
                        "{flux:?} over the channel's {area} m² is an exitance of {exitance:?}, \
                         above the {MAX_EXITANCE:e} a basis stores"
                    ),
                });
            }
            Some(exitance)
        }
        (None, None) => None,
    })
}

/// Every surface whose material emits is driven by a channel.
fn check_driven(
    surfaces: &[Surface],
    raw: &[RawSurface],
    channel_of_surface: &[Option<usize>],
    material_emission: &[Vec<f64>],
) -> Result<(), SceneError> {
    for (i, s) in surfaces.iter().enumerate() {
        if channel_of_surface[i].is_none() && material_emission[i].iter().any(|&x| x > 0.0) {
            return Err(SceneError::Emitter {
                at: raw[i].material_at.clone(),
                surface: s.name.clone(),
                message: format!(
                    "its material `{}` emits but no channel drives it; add it to a [[channel]]",
                    s.material
                ),
            });
        }
    }
    Ok(())
}
