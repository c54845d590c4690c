//! `eigenrad verify`'s report as markdown: one function per section, in the order they
//! appear.

use std::fmt::Write as _;

use super::{CaseKind, FormulationReport, Metric, VerifyReport};

/// The report as markdown tables.
pub fn markdown(r: &VerifyReport) -> String {
    let mut s = String::new();
    introduction(&mut s, r);
    smallest_p_table(&mut s, r);
    for f in &r.formulations {
        formulation_table(&mut s, r, f);
    }
    if !r.zones.is_empty() || !r.sensors.is_empty() {
        outputs_table(&mut s, r);
    }
    baseline(&mut s, r);
    s
}

fn sci(x: Option<f64>) -> String {
    x.map_or("—".into(), |v| format!("{v:.1e}"))
}

fn p_text(p: Option<usize>) -> String {
    p.map_or("not reached".into(), |p| p.to_string())
}

/// The title, the scene and what the cases and errors are.
fn introduction(s: &mut String, r: &VerifyReport) {
    let _ = writeln!(s, "# Accuracy of the eigenbasis: {}\n", r.scene);
    let _ = writeln!(
        s,
        "Scene `{}`: {} patches, {} band(s) in {}; {} channel(s), {} sensor(s), {} zone(s). \
         Modes available: {}.\n",
        r.path,
        r.patches,
        r.bands,
        r.unit,
        r.channels.len(),
        r.sensors.len(),
        r.zones.len(),
        r.modes.last().copied().unwrap_or(0)
    );
    let count = |k: CaseKind| {
        r.formulations
            .first()
            .map_or(0, |f| f.cases.iter().filter(|c| c.kind == k).count())
    };
    let _ = writeln!(
        s,
        "Cases: {} channel(s) alone at level 1; {} random channel mix(es) (every channel at a \
         random level in [0, 1]); {} random emitter pattern(s) (a random fifth of the patches, \
         each at a random exitance up to the brightest channel's, no channel). Every error is \
         relative to the exact dense solve (LU) of the same scene and form factors, worst \
         spectral band, worst case of its kind: **patches** = area-weighted RMS of the \
         per-patch exitance error over the RMS exitance; **zones**, **sensors** = worst \
         |E − E_exact| / E_exact over the zones or sensors. Computed in f64 (truncation alone; \
         `eigenrad build` reports the runtime's f32 on top).\n",
        count(CaseKind::Channel),
        count(CaseKind::ChannelMix),
        count(CaseKind::EmitterPattern)
    );
}

/// The smallest p within 1 % for patch exitance, every zone and every sensor.
fn smallest_p_table(s: &mut String, r: &VerifyReport) {
    let _ = writeln!(s, "## Smallest p within 1 %, every case\n");
    let _ = write!(s, "| reading |");
    for f in &r.formulations {
        let _ = write!(s, " {} |", f.formulation);
    }
    let _ = writeln!(s);
    let _ = writeln!(s, "|---|{}", "---:|".repeat(r.formulations.len()));
    let mut rows: Vec<(String, Vec<Option<usize>>)> = vec![(
        "patch exitance".into(),
        r.formulations
            .iter()
            .map(|f| r.smallest_p(0.01, |t| f.worst(None, Metric::Patches, t).unwrap_or(0.0)))
            .collect(),
    )];
    for (z, name) in r.zones.iter().enumerate() {
        rows.push((
            format!("zone `{name}`"),
            r.formulations
                .iter()
                .map(|f| r.smallest_p(0.01, |t| f.worst_output(true, z, t)))
                .collect(),
        ));
    }
    for (i, name) in r.sensors.iter().enumerate() {
        rows.push((
            format!("sensor `{name}`"),
            r.formulations
                .iter()
                .map(|f| r.smallest_p(0.01, |t| f.worst_output(false, i, t)))
                .collect(),
        ));
    }
    for (name, ps) in rows {
        let _ = write!(s, "| {name} |");
        for p in ps {
            let _ = write!(s, " {} |", p_text(p));
        }
        let _ = writeln!(s);
    }
    let _ = writeln!(s);
}

/// One formulation's worst error by case kind and metric, at every tested p.
fn formulation_table(s: &mut String, r: &VerifyReport, f: &FormulationReport) {
    let _ = writeln!(
        s,
        "## `{}`: worst relative error by case kind\n",
        f.formulation
    );
    let _ = write!(s, "| p | basis bytes (f32) |");
    for k in CaseKind::ALL {
        for m in Metric::ALL {
            let _ = write!(s, " {}: {} |", k.label(), m.label());
        }
    }
    let _ = writeln!(s);
    let _ = writeln!(s, "|---:|---:|{}", "---:|".repeat(9));
    for (t, p) in r.modes.iter().enumerate() {
        let _ = write!(s, "| {p} | {} |", f.basis_bytes[t]);
        for k in CaseKind::ALL {
            for m in Metric::ALL {
                let _ = write!(s, " {} |", sci(f.worst(Some(k), m, t)));
            }
        }
        let _ = writeln!(s);
    }
    let _ = writeln!(s);
}

/// Each zone and sensor, worst over every case, at every tested p.
fn outputs_table(s: &mut String, r: &VerifyReport) {
    let _ = writeln!(s, "## Each zone and sensor, worst over every case\n");
    let _ = write!(s, "| p |");
    let mut columns: Vec<(bool, usize, &str)> = Vec::new();
    for (z, name) in r.zones.iter().enumerate() {
        columns.push((true, z, name));
    }
    for (i, name) in r.sensors.iter().enumerate() {
        columns.push((false, i, name));
    }
    for (zone, _, name) in &columns {
        for f in &r.formulations {
            let what = if *zone { "zone" } else { "sensor" };
            let _ = write!(s, " {what} `{name}` {} |", f.formulation);
        }
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "|---:|{}",
        "---:|".repeat(columns.len() * r.formulations.len())
    );
    for (t, p) in r.modes.iter().enumerate() {
        let _ = write!(s, "| {p} |");
        for (zone, index, _) in &columns {
            for f in &r.formulations {
                let _ = write!(s, " {:.1e} |", f.worst_output(*zone, *index, t));
            }
        }
        let _ = writeln!(s);
    }
    let _ = writeln!(s);
}

/// The exact per-channel superposition: its error and its storage against the split basis'.
fn baseline(s: &mut String, r: &VerifyReport) {
    let _ = writeln!(s, "## Baseline: exact per-channel superposition\n");
    let _ = writeln!(
        s,
        "The exact response `(I − R F)⁻¹ e_c` of each of the {} channel(s), scaled by the \
         levels and added: exact for any channel state by construction (the figures below are \
         the measured rounding), but it cannot represent an emitter pattern that is not a \
         combination of the fixed channels.\n",
        r.channels.len()
    );
    let _ = writeln!(s, "| case kind | patches | zones | sensors |");
    let _ = writeln!(s, "|---|---:|---:|---:|");
    for k in CaseKind::ALL {
        let cells: Vec<String> = match (k, r.baseline.channel_error) {
            (CaseKind::EmitterPattern, _) | (_, None) => {
                vec!["not representable".into(); 3]
            }
            (_, Some(e)) => {
                let has = |m: Metric| match m {
                    Metric::Patches => true,
                    Metric::Zones => !r.zones.is_empty(),
                    Metric::Sensors => !r.sensors.is_empty(),
                };
                Metric::ALL
                    .iter()
                    .zip(e)
                    .map(|(m, v)| {
                        if has(*m) {
                            format!("{v:.1e}")
                        } else {
                            "—".into()
                        }
                    })
                    .collect()
            }
        };
        let _ = writeln!(s, "| {} | {} |", k.label(), cells.join(" | "));
    }
    let split_bytes = r
        .formulations
        .first()
        .map(|f| {
            r.modes
                .iter()
                .zip(&f.basis_bytes)
                .map(|(p, b)| format!("{b} at p = {p}"))
                .collect::<Vec<_>>()
        })
        .unwrap_or_default();
    let _ = writeln!(
        s,
        "\nStorage in f32: {} bytes for per-patch exitance and every sensor and zone \
         (`4 (n + outputs) m bands`, n × m = {} × {}), {} bytes for the sensors and zones \
         alone. The split basis, which also takes any emitter pattern: {}.\n",
        r.baseline.bytes,
        r.patches,
        r.channels.len(),
        r.baseline.output_bytes,
        pick(&split_bytes)
    );
}

/// A few entries of a long list: first, some middle ones, last.
fn pick(items: &[String]) -> String {
    if items.len() <= 4 {
        return items.join(", ");
    }
    let idx = [0, items.len() / 3, 2 * items.len() / 3, items.len() - 1];
    idx.iter()
        .map(|&i| items[i].clone())
        .collect::<Vec<_>>()
        .join(", ")
}
