//! `asperity inspect FILE [--channel NAME] [--png OUT]`: what a topography file holds (format,
//! instrument, channels), its statistics, and optionally a height-map image.

use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result};

use asperity::engine::value::Field;
use asperity::nodes::validity;
use asperity::surface::io::{
    detect_format, parse_topography_channel, read_topography_bytes, LineScan, ScaleSource,
    Topography, TopographyData, METADATA_INSTRUMENT, METADATA_VENDOR,
};
use asperity::surface::{
    amplitude_statistics, functional_parameters, AmplitudeStatistics, Boundary, FunctionalOptions,
    FunctionalParameters, HeightMap,
};
use asperity::units::Dimension;
use asperity::vocabulary::metrics::{DX, DY, SQ};
use asperity::vocabulary::surface_metrics::{SA, SDQ, SDR_PERCENT, SKU, SP, SSK, SV, SZ};

/// Arguments of `asperity inspect`.
#[derive(Debug, clap::Args)]
pub struct InspectArgs {
    /// The topography file.
    file: PathBuf,
    /// Write the height map as a PNG image (grey levels from the lowest to the highest point,
    /// missing points in red).
    #[arg(long, value_name = "OUT")]
    png: Option<PathBuf>,
    /// The channel to read, for a file holding several (listed under `channels:`); default:
    /// the height channel.
    #[arg(long, value_name = "NAME")]
    channel: Option<String>,
}

pub fn inspect(args: InspectArgs) -> Result<ExitCode> {
    let bytes = read_topography_bytes(&args.file)?;
    let reader = detect_format(&args.file, &bytes);
    let topo = parse_topography_channel(&args.file, &bytes, args.channel.as_deref())?;
    println!("file:      {}", args.file.display());
    if let Some(reader) = reader {
        println!("format:    {} ({})", reader.name, reader.description);
    }
    describe_source(&topo);
    let source = match reader {
        Some(r) => format!("{} ({})", args.file.display(), r.name),
        None => args.file.display().to_string(),
    };
    match &topo.data {
        TopographyData::Areal(map) => describe_map(map, topo.spacing, topo.height_unit, &source)?,
        TopographyData::Line(line) => describe_line(line, &source)?,
    }
    for (k, v) in &topo.metadata {
        println!("  {k}: {v}");
    }
    if let Some(out) = &args.png {
        match &topo.data {
            TopographyData::Areal(map) => {
                write_png(map, out)?;
                println!("image:     {}", out.display());
            }
            TopographyData::Line(_) => {
                anyhow::bail!("--png needs an areal topography, not a line scan")
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// The instrument (when the file names it) and the channels, the one read marked.
fn describe_source(topo: &Topography) {
    let instrument: Vec<&str> = [METADATA_VENDOR, METADATA_INSTRUMENT]
        .iter()
        .filter_map(|k| topo.metadata.get(*k).map(String::as_str))
        .filter(|v| !v.trim().is_empty())
        .collect();
    if !instrument.is_empty() {
        println!("instrument: {}", instrument.join(" "));
    }
    let read = topo.channel.as_deref().unwrap_or_default();
    let channels: Vec<String> = topo
        .channels
        .iter()
        .map(|c| {
            if c == read {
                format!("{c} (read)")
            } else {
                c.clone()
            }
        })
        .collect();
    println!("channels:  {}", channels.join(", "));
}

/// `source` names the file and its format in errors.
fn describe_map(
    map: &HeightMap,
    spacing: ScaleSource,
    height_unit: ScaleSource,
    source: &str,
) -> Result<()> {
    let (lx, ly) = map.size();
    println!("kind:      areal map");
    println!("grid:      {} × {} points (nx × ny)", map.nx(), map.ny());
    match spacing {
        ScaleSource::File => {
            println!(
                "spacing:   dx = {:.6e} m, dy = {:.6e} m",
                map.dx(),
                map.dy()
            );
            println!("size:      {lx:.6e} m × {ly:.6e} m");
        }
        ScaleSource::Assumed => {
            println!("spacing:   not in the file (this format stores no lateral calibration)");
            println!(
                "           give it in the surface node: `pixel_size: 0.5 um` (or [dx, dy]) or \
                 `size: [Lx, Ly]`"
            );
        }
    }
    match height_unit {
        ScaleSource::File => {
            println!("units:     heights and lengths in metres (converted from the file's units)")
        }
        ScaleSource::Assumed => println!(
            "units:     height unit not in the file: the values are read as metres (check them)"
        ),
    }
    let a = amplitude_statistics(map, Boundary::Open)?;
    check_values(map, spacing, &a, source)?;
    let functional = functional_parameters(map, FunctionalOptions::default())?;
    println!(
        "missing:   {} of {} points ({:.3} %)",
        a.missing_count,
        a.missing_count + a.valid_count,
        100.0 * a.missing_count as f64 / (a.missing_count + a.valid_count) as f64
    );
    println!("statistics over valid points, mean removed, no levelling (ISO 25178-2):");
    println!("  Sq  = {:.9e} m", a.sq);
    println!("  Sa  = {:.9e} m", a.sa);
    println!("  Sp  = {:.9e} m", a.sp);
    println!("  Sv  = {:.9e} m", a.sv);
    println!("  Sz  = {:.9e} m", a.sz);
    let opt = |v: Option<f64>| v.map_or(String::from("undefined"), |v| format!("{v:.7}"));
    println!("  Ssk = {}", opt(a.ssk));
    println!("  Sku = {}", opt(a.sku));
    print_functional(&functional);
    if spacing == ScaleSource::Assumed {
        println!("  Sdq, Sdr: need the spacing");
        return Ok(());
    }
    println!("  Sdq = {} (central differences)", opt(a.sdq));
    println!(
        "  Sdr = {} %",
        a.sdr_percent
            .map_or(String::from("undefined"), |v| format!("{v:.5}"))
    );
    Ok(())
}

/// The ISO 25178-2 functional and volume parameters at the default material ratios.
fn print_functional(f: &FunctionalParameters) {
    println!("functional parameters (material ratio curve; volumes at p = 10 %, q = 80 %):");
    println!("  Sk  = {:.9e} m", f.sk);
    println!("  Spk = {:.9e} m", f.spk);
    println!("  Svk = {:.9e} m", f.svk);
    println!("  Smr1 = {:.5} %", 100.0 * f.smr1);
    println!("  Smr2 = {:.5} %", 100.0 * f.smr2);
    println!("  Sxp = {:.9e} m (p = 2.5 %, q = 50 %)", f.sxp);
    println!("  Vmp = {:.9e} m^3/m^2", f.vmp);
    println!("  Vmc = {:.9e} m^3/m^2", f.vmc);
    println!("  Vvc = {:.9e} m^3/m^2", f.vvc);
    println!("  Vvv = {:.9e} m^3/m^2", f.vvv);
}

/// The surface node's validity rules on what `inspect` prints: an impossible value (a spacing
/// that is not a positive length, an Sq that overflowed) is an error naming the file (`source`)
/// and the value, heights larger than the field of view a warning on stderr.
fn check_values(
    map: &HeightMap,
    spacing: ScaleSource,
    a: &AmplitudeStatistics,
    source: &str,
) -> Result<()> {
    let len = |name: &'static str, v: f64| Field::float(name, v, Dimension::Length);
    let mut fields = vec![
        len(SQ, a.sq),
        len(SA, a.sa),
        len(SP, a.sp),
        len(SV, a.sv),
        len(SZ, a.sz),
    ];
    let optional = [(SSK, a.ssk), (SKU, a.sku)];
    if spacing == ScaleSource::File {
        fields.extend([len(DX, map.dx()), len(DY, map.dy())]);
        let slopes = [(SDQ, a.sdq), (SDR_PERCENT, a.sdr_percent)];
        fields.extend(
            slopes
                .into_iter()
                .filter_map(|(n, v)| v.map(|v| Field::float(n, v, Dimension::Dimensionless))),
        );
    }
    fields.extend(
        optional
            .into_iter()
            .filter_map(|(n, v)| v.map(|v| Field::float(n, v, Dimension::Dimensionless))),
    );
    validity::check_fields(validity::SURFACE, &fields)
        .map_err(|e| anyhow::anyhow!("{source}: {}: {e}", impossible("this file's values")))?;
    if spacing == ScaleSource::File {
        let (lx, ly) = map.size();
        if let Some(warning) = validity::cross::surface_size(a.sq, lx, ly) {
            eprintln!("warning: {warning}");
        }
    }
    Ok(())
}

/// `source` names the file and its format in errors.
fn describe_line(line: &LineScan, source: &str) -> Result<()> {
    let valid: Vec<f64> = line.z.iter().copied().filter(|z| !z.is_nan()).collect();
    println!("kind:      line scan (profile)");
    println!(
        "points:    {} ({} missing)",
        line.z.len(),
        line.z.len() - valid.len()
    );
    if let (Some(first), Some(last)) = (line.x.first(), line.x.last()) {
        println!("length:    {:.6e} m", last - first);
    }
    if !valid.is_empty() {
        let mean = valid.iter().sum::<f64>() / valid.len() as f64;
        let rq =
            (valid.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / valid.len() as f64).sqrt();
        let field = [Field::float(SQ, rq, Dimension::Length)];
        validity::check_fields(validity::SURFACE, &field).map_err(|e| {
            anyhow::anyhow!(
                "{source}: {} (its Rq as Sq): {e}",
                impossible("this profile's values")
            )
        })?;
        println!("Rq (point average, no levelling) = {rq:.9e} m");
    }
    Ok(())
}

/// The sentence for values a reader accepted but no surface can have: `what` is not physically
/// possible, and the likely cause.
fn impossible(what: &str) -> String {
    format!(
        "{what} are not physically possible (the reader accepted the file: a damaged height \
         scale, spacing or data block is the likely cause; compare with the instrument's software)"
    )
}

fn write_png(map: &HeightMap, out: &Path) -> Result<()> {
    let z = map.heights();
    let (lo, hi) = z
        .iter()
        .filter(|v| !v.is_nan())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let span = if hi > lo { hi - lo } else { 1.0 };
    let mut rgb = Vec::with_capacity(map.nx() * map.ny() * 3);
    for v in z.iter() {
        if v.is_nan() {
            rgb.extend_from_slice(&[200, 0, 0]);
        } else {
            let g = (((v - lo) / span) * 255.0).round().clamp(0.0, 255.0) as u8;
            rgb.extend_from_slice(&[g, g, g]);
        }
    }
    let file =
        std::fs::File::create(out).with_context(|| format!("cannot create {}", out.display()))?;
    let mut encoder = png::Encoder::new(BufWriter::new(file), map.nx() as u32, map.ny() as u32);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&rgb)?;
    Ok(())
}
