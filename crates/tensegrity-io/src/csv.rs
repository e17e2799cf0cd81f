//! CSV tables through the `csv` crate: one header row whose column names carry the units
//! (`t [s]`, `azimuth_rad`, `force_N`), then one record per row.
//!
//! The generic [`write_rows`] writes any `Serialize` row type, its field names (or serde
//! renames) being the header; numbers are written as the shortest decimal text that reads back
//! to the same `f64`. The specific writers keep the number layout the command-line tool has
//! always written (`{}`, `{:e}`, or [`Sci17`] = `{:.17e}`); all of them read back exactly. The specific writers below produce the files of the command-line
//! tool, each a single call, usually inside [`crate::write_file`]:
//!
//! ```
//! use tensegrity_io::{csv, write_file};
//! let path = std::env::temp_dir().join(format!("tensegrity-io-grid-{}.csv", std::process::id()));
//! let n = write_file(&path, |w| csv::write_friction_grid(w, &[(0.5, 0.1, 0.25)]))?;
//! assert_eq!(n, 1);
//! let text = std::fs::read_to_string(&path).unwrap();
//! assert_eq!(text, "sigma,epsilon,normalized_friction\n0.5,0.1,0.25\n");
//! # std::fs::remove_file(&path).unwrap();
//! # Ok::<(), tensegrity_io::IoError>(())
//! ```

use crate::error::{IoError, Result};
use michell3d::complexity::MassRow;
use michell3d::extra_strings::GammaSweepRow;
use michell3d::signmap::SignMapRow;
use serde::{Serialize, Serializer};
use std::io::Write;
use tensegrity_dynamics::SimulationResult;
use wheel_rolling::RollingSample;

/// An `f64` written as `{:.17e}` (17 digits after the point: exact, fixed layout).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sci17(pub f64);

impl Serialize for Sci17 {
    fn serialize<S: Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        serializer.collect_str(&format_args!("{:.17e}", self.0))
    }
}

/// Serializes an `f64` with `{}` (Rust's shortest round-trip decimal, never an exponent).
fn plain<S: Serializer>(v: &f64, serializer: S) -> std::result::Result<S::Ok, S::Error> {
    serializer.collect_str(v)
}

/// Serializes an `f64` with `{:e}` (shortest round-trip mantissa and an exponent).
fn exponent<S: Serializer>(v: &f64, serializer: S) -> std::result::Result<S::Ok, S::Error> {
    serializer.collect_str(&format_args!("{v:e}"))
}

fn csv_error(what: &'static str) -> impl Fn(::csv::Error) -> IoError {
    move |e| IoError::Stream {
        what,
        source: e.into(),
    }
}

/// Writes `rows` with a header row taken from the field names of `R` (written before the
/// first row: no rows, no header); returns the number of rows.
///
/// ```
/// #[derive(serde::Serialize)]
/// struct Row {
///     azimuth_rad: f64,
///     #[serde(rename = "force_N")]
///     force: f64,
/// }
/// let mut out = Vec::new();
/// let n = tensegrity_io::csv::write_rows(&mut out, "forces", [Row { azimuth_rad: 0.5, force: -2.0 }])?;
/// assert_eq!((n, String::from_utf8(out).unwrap()), (1, "azimuth_rad,force_N\n0.5,-2.0\n".into()));
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
pub fn write_rows<W: Write, R: Serialize>(
    out: W,
    what: &'static str,
    rows: impl IntoIterator<Item = R>,
) -> Result<usize> {
    let mut w = ::csv::Writer::from_writer(out);
    let mut n = 0;
    for row in rows {
        w.serialize(row).map_err(csv_error(what))?;
        n += 1;
    }
    w.flush().map_err(IoError::stream(what))?;
    Ok(n)
}

/// Writes an explicit header and rows of text fields; returns the number of rows.
///
/// ```
/// let mut out = Vec::new();
/// tensegrity_io::csv::write_table(&mut out, "table", &["t [s]", "x [m]"], [vec!["0".to_string(), "1.5".into()]])?;
/// assert_eq!(String::from_utf8(out).unwrap(), "t [s],x [m]\n0,1.5\n");
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
pub fn write_table<W: Write, H: AsRef<[u8]>, F: AsRef<[u8]>>(
    out: W,
    what: &'static str,
    header: &[H],
    rows: impl IntoIterator<Item = Vec<F>>,
) -> Result<usize> {
    let mut w = ::csv::Writer::from_writer(out);
    w.write_record(header).map_err(csv_error(what))?;
    let mut n = 0;
    for row in rows {
        w.write_record(&row).map_err(csv_error(what))?;
        n += 1;
    }
    w.flush().map_err(IoError::stream(what))?;
    Ok(n)
}

/// The node trajectory of a simulation: `t [s]`, then `n{i}_x [m]`, `n{i}_y [m]`,
/// `n{i}_z [m]` for every node, one row per sample holding node positions, all `{:.17e}`.
///
/// ```
/// use tensegrity_core::{Bar, Structure};
/// use tensegrity_dynamics::{Simulation, SimulationSettings};
/// let s = Structure::builder().nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1).mass(1.0)).build().unwrap();
/// let mut settings = SimulationSettings { t_end: 0.1, output_interval: Some(0.05), ..Default::default() };
/// settings.quantities.nodes = true;
/// let r = Simulation::new(&s, settings).unwrap().run().unwrap();
/// let mut out = Vec::new();
/// assert_eq!(tensegrity_io::csv::write_trajectory(&mut out, &r)?, 3);
/// assert!(String::from_utf8(out).unwrap().starts_with("t [s],n0_x [m],n0_y [m],n0_z [m],n1_x [m]"));
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
pub fn write_trajectory<W: Write>(out: W, result: &SimulationResult) -> Result<usize> {
    let mut header = vec!["t [s]".to_string()];
    for i in 0..result.final_nodes.len() {
        for axis in ["x", "y", "z"] {
            header.push(format!("n{i}_{axis} [m]"));
        }
    }
    let rows = result.samples.iter().filter_map(|s| {
        let nodes = s.nodes.as_ref()?;
        let mut row = vec![format!("{:.17e}", s.t)];
        for p in nodes {
            row.extend([p.x, p.y, p.z].map(|v| format!("{v:.17e}")));
        }
        Some(row)
    });
    write_table(out, "trajectory CSV", &header, rows)
}

/// One row of a rolling history (column names with units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RollingRow {
    /// Time (s).
    #[serde(rename = "t", serialize_with = "plain")]
    pub t_s: f64,
    /// Axle position along the slope, downhill (m).
    #[serde(rename = "axle_s", serialize_with = "plain")]
    pub axle_s_m: f64,
    /// Axle height above the slope (m).
    #[serde(rename = "axle_h", serialize_with = "plain")]
    pub axle_h_m: f64,
    /// Angular velocity about the axle (rad/s, positive rolling downhill).
    #[serde(rename = "omega", serialize_with = "plain")]
    pub omega_rad_s: f64,
    /// Position of the pivoting contact pair (m).
    #[serde(serialize_with = "plain")]
    pub pivot_m: f64,
    /// Normal contact force (N).
    #[serde(rename = "normal_N", serialize_with = "plain")]
    pub normal_n: f64,
    /// Tangential contact force (N).
    #[serde(rename = "tangential_N", serialize_with = "plain")]
    pub tangential_n: f64,
    /// Kinetic plus gravitational energy (J).
    #[serde(rename = "energy_J", serialize_with = "plain")]
    pub energy_j: f64,
    /// Mean slip speed of the loaded contact nodes (m/s).
    #[serde(serialize_with = "plain")]
    pub slip_m_s: f64,
}

impl From<&RollingSample> for RollingRow {
    fn from(s: &RollingSample) -> Self {
        Self {
            t_s: s.t,
            axle_s_m: s.s,
            axle_h_m: s.h,
            pivot_m: s.pivot,
            omega_rad_s: s.omega,
            normal_n: s.normal,
            tangential_n: s.tangential,
            energy_j: s.energy,
            slip_m_s: s.slip,
        }
    }
}

/// The rolling history of a wheel:
/// `t,axle_s,axle_h,omega,pivot_m,normal_N,tangential_N,energy_J,slip_m_s` (s, m, m, rad/s, …;
/// the first four are the `tensegrity roll --out` contract).
pub fn write_rolling_history<W: Write>(out: W, samples: &[RollingSample]) -> Result<usize> {
    write_rows(
        out,
        "rolling history CSV",
        samples.iter().map(RollingRow::from),
    )
}

/// The tip-over friction grid of Fig. 3.13: `sigma,epsilon,normalized_friction` from
/// `(σ, ε, F_f/F_e)` triples (all dimensionless).
pub fn write_friction_grid<W: Write>(out: W, rows: &[(f64, f64, f64)]) -> Result<usize> {
    #[derive(Serialize)]
    struct Row {
        #[serde(serialize_with = "plain")]
        sigma: f64,
        #[serde(serialize_with = "plain")]
        epsilon: f64,
        #[serde(serialize_with = "plain")]
        normalized_friction: f64,
    }
    let rows = rows
        .iter()
        .map(|&(sigma, epsilon, normalized_friction)| Row {
            sigma,
            epsilon,
            normalized_friction,
        });
    write_rows(out, "friction grid CSV", rows)
}

/// One point of the work–precision study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorkPrecisionRow {
    /// Scene name.
    pub scene: String,
    /// Integrator name.
    pub integrator: String,
    /// dt (s, fixed-step integrators) or rtol (adaptive).
    #[serde(rename = "parameter (dt [s] or rtol)", serialize_with = "exponent")]
    pub parameter: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Force evaluations.
    pub rhs_evals: u64,
    /// Max node-position error at the end time (m).
    #[serde(rename = "error [m]", serialize_with = "exponent")]
    pub error_m: f64,
    /// Integration wall time (s).
    #[serde(rename = "wall_time [s]", serialize_with = "exponent")]
    pub wall_time_s: f64,
}

/// The work–precision points:
/// `scene,integrator,parameter (dt [s] or rtol),steps,rhs_evals,error [m],wall_time [s]`.
pub fn write_work_precision<W: Write>(out: W, rows: &[WorkPrecisionRow]) -> Result<usize> {
    write_rows(out, "work-precision CSV", rows)
}

/// Michell sign maps:
/// `member,parent,child,azimuth_rad,polar_rad,force_density_N_per_m,sign`, angles and force
/// densities `{:.17e}` (from [`michell3d::signmap::sign_map_rows`]).
pub fn write_sign_maps<W: Write>(
    out: W,
    rows: impl IntoIterator<Item = SignMapRow>,
) -> Result<usize> {
    #[derive(Serialize)]
    struct Row {
        member: usize,
        parent: String,
        child: String,
        azimuth_rad: Sci17,
        polar_rad: Sci17,
        #[serde(rename = "force_density_N_per_m")]
        force_density: Sci17,
        sign: i8,
    }
    let rows = rows.into_iter().map(|r| Row {
        member: r.member,
        parent: r.parent,
        child: r.child,
        azimuth_rad: Sci17(r.azimuth_rad),
        polar_rad: Sci17(r.polar_rad),
        force_density: Sci17(r.force_density_n_per_m),
        sign: r.sign,
    });
    write_rows(out, "sign map CSV", rows)
}

/// A Michell γ sweep: `polar_rad,member,kind,force_N` (`kind` = `base` or `extra`), numbers
/// `{:.17e}` (from [`michell3d::extra_strings::GammaSweep::rows`]).
pub fn write_gamma_sweep<W: Write>(
    out: W,
    rows: impl IntoIterator<Item = GammaSweepRow>,
) -> Result<usize> {
    #[derive(Serialize)]
    struct Row {
        polar_rad: Sci17,
        member: usize,
        kind: michell3d::extra_strings::SweepMember,
        #[serde(rename = "force_N")]
        force: Sci17,
    }
    let rows = rows.into_iter().map(|r| Row {
        polar_rad: Sci17(r.polar_rad),
        member: r.member,
        kind: r.kind,
        force: Sci17(r.force_n),
    });
    write_rows(out, "gamma sweep CSV", rows)
}

/// The Michell mass–complexity table of Fig. 4.18: `complexity,delta,normalized_yield_mass,
/// yield_mass_kg,yield_buckling_mass_kg,sign_changes_vs_planar`.
/// Numbers with `{}` (exact; today's layout wrote the masses with 13 digits only).
pub fn write_mass_table<W: Write>(out: W, rows: &[MassRow]) -> Result<usize> {
    #[derive(Serialize)]
    struct Row {
        complexity: usize,
        #[serde(serialize_with = "plain")]
        delta: f64,
        #[serde(serialize_with = "plain")]
        normalized_yield_mass: f64,
        #[serde(serialize_with = "plain")]
        yield_mass_kg: f64,
        #[serde(serialize_with = "plain")]
        yield_buckling_mass_kg: f64,
        sign_changes_vs_planar: usize,
    }
    let rows = rows.iter().map(|r| Row {
        complexity: r.complexity,
        delta: r.delta,
        normalized_yield_mass: r.normalized_yield_mass,
        yield_mass_kg: r.yield_mass_kg,
        yield_buckling_mass_kg: r.yield_buckling_mass_kg,
        sign_changes_vs_planar: r.sign_changes_vs_planar,
    });
    write_rows(out, "mass table CSV", rows)
}

/// A labelled curve: (group value, (x, y) points).
pub type Curve = (String, Vec<(f64, f64)>);

/// Reads columns `x` and `y` of a CSV table (a sweep's results, a trajectory…) as curves, one
/// per distinct value of column `group` (in order of first appearance; one unnamed curve
/// without `group`). Lines starting with `#` are comments; rows whose `status` column (if any)
/// is not `ok`, or whose x or y is not a finite number, are left out.
///
/// ```
/// let path = std::env::temp_dir().join(format!("series-doc-{}.csv", std::process::id()));
/// std::fs::write(&path, "# units: …\ncase,n,mass,status\n0,8,1.5,ok\n1,12,2.5,ok\n2,16,,error\n").unwrap();
/// let curves = tensegrity_io::csv::read_series(&path, "n", "mass", None)?;
/// assert_eq!(curves, vec![(String::new(), vec![(8.0, 1.5), (12.0, 2.5)])]);
/// assert!(tensegrity_io::csv::read_series(&path, "n", "volume", None).is_err());
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
pub fn read_series(
    path: &std::path::Path,
    x: &str,
    y: &str,
    group: Option<&str>,
) -> Result<Vec<Curve>> {
    read_series_where(path, x, y, group, &[])
}

/// The number a cell holds: a plain number as written, an angle written with its unit
/// (`30deg`, `pi/6`, `3pi/4`: the sweep axes of angle parameters) in degrees.
///
/// ```
/// use tensegrity_io::csv::{cell_value, is_angle};
/// assert_eq!(cell_value("0.25"), Some(0.25));
/// assert!((cell_value("pi/6").unwrap() - 30.0).abs() < 1e-12);
/// assert_eq!(cell_value("30deg"), Some(30.0));
/// assert_eq!(cell_value("rigid"), None);
/// assert!(is_angle("45deg") && !is_angle("0.5"));
/// ```
pub fn cell_value(text: &str) -> Option<f64> {
    let text = text.trim();
    // degrees as written (a round trip through radians would turn 30 into 29.999…)
    if let Some(v) = text
        .strip_suffix("deg")
        .and_then(|d| d.trim().parse::<f64>().ok())
        .filter(|v| v.is_finite())
    {
        return Some(v);
    }
    match text.parse::<f64>() {
        Ok(v) => Some(v),
        Err(_) if is_angle(text) => tensegrity_core::angle::parse_angle(text)
            .ok()
            .map(f64::to_degrees),
        Err(_) => None,
    }
}

/// Whether a cell is an angle written with its unit (`deg` or `pi`), not a plain number.
pub fn is_angle(text: &str) -> bool {
    let t = text.trim().to_ascii_lowercase();
    (t.ends_with("deg") || t.contains("pi")) && tensegrity_core::angle::parse_angle(&t).is_ok()
}

/// Whether the column `name` of a sweep's CSV holds angles with units (its first ok row's
/// cell, see [`is_angle`]); `false` for a column that is not there.
pub fn column_is_angle(path: &std::path::Path, name: &str) -> Result<bool> {
    let mut reader = ::csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(path)
        .map_err(csv_error("CSV file"))?;
    let header = reader.headers().map_err(csv_error("CSV header"))?.clone();
    let Some(i) = header.iter().position(|h| h == name) else {
        return Ok(false);
    };
    let first = reader.records().flatten().next();
    Ok(first.is_some_and(|r| r.get(i).is_some_and(is_angle)))
}

/// [`read_series`] of the rows whose columns hold exactly the given texts (`filter`: pairs
/// column, value), e.g. one tread width of a sweep over several:
///
/// ```
/// let path = std::env::temp_dir().join(format!("series-where-{}.csv", std::process::id()));
/// std::fs::write(&path, "case,n,T,mass,status\n0,8,0.4,1.5,ok\n1,8,0.5,2.5,ok\n").unwrap();
/// let curves = tensegrity_io::csv::read_series_where(&path, "n", "mass", None, &[("T", "0.5")])?;
/// assert_eq!(curves, vec![(String::new(), vec![(8.0, 2.5)])]);
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
pub fn read_series_where(
    path: &std::path::Path,
    x: &str,
    y: &str,
    group: Option<&str>,
    filter: &[(&str, &str)],
) -> Result<Vec<Curve>> {
    let text = std::fs::read_to_string(path).map_err(|source| IoError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let body: String = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| format!("{l}\n"))
        .collect();
    let mut reader = ::csv::Reader::from_reader(body.as_bytes());
    let header = reader.headers().map_err(csv_error("CSV header"))?.clone();
    let column = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| IoError::MissingColumn {
                path: path.to_path_buf(),
                column: name.to_string(),
            })
    };
    let (xi, yi) = (column(x)?, column(y)?);
    let gi = group.map(column).transpose()?;
    let wanted = filter
        .iter()
        .map(|&(c, v)| Ok((column(c)?, v)))
        .collect::<Result<Vec<_>>>()?;
    let status = header.iter().position(|h| h == "status");
    let mut curves: Vec<Curve> = Vec::new();
    for record in reader.records() {
        let record = record.map_err(csv_error("CSV row"))?;
        if status.is_some_and(|s| record.get(s) != Some("ok")) {
            continue;
        }
        if wanted.iter().any(|&(i, v)| record.get(i) != Some(v)) {
            continue;
        }
        let num = |i: usize| record.get(i).and_then(cell_value);
        let (Some(xv), Some(yv)) = (num(xi), num(yi)) else {
            continue;
        };
        if !(xv.is_finite() && yv.is_finite()) {
            continue;
        }
        let label = gi.and_then(|g| record.get(g)).unwrap_or("").to_string();
        match curves.iter_mut().find(|(l, _)| *l == label) {
            Some((_, points)) => points.push((xv, yv)),
            None => curves.push((label, vec![(xv, yv)])),
        }
    }
    Ok(curves)
}
