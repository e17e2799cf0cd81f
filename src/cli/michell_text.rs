//! The readable report of `tensegrity michell`: geometry, load and counts, one row per
//! member, masses, and the extra strings' check (§4.6–4.7).

use michell3d::{ExtraStringsCheck, MemberKind, Method, MichellReport, MichellRun};

/// The readable report of a run: the analysis, then the extra strings' check.
pub fn report(run: &MichellRun) -> String {
    let mut s = report_text(&run.analysis.report);
    if let Some(check) = &run.extra {
        s += &extra_text(check);
    }
    s
}

fn member_row(s: &mut String, m: &michell3d::report::MemberReport) {
    use std::fmt::Write;
    let _ = writeln!(
        s,
        "{:>16} {:>16} {:>12.6} {:>16.6e} {:>14.6e} {:>6} {:>9}",
        tuple(&m.parent),
        tuple(&m.child),
        m.length,
        m.force_density,
        m.force,
        m.kind.as_str(),
        michell3d::report::governing_name(m.governing)
    );
}

fn tuple(t: &[usize]) -> String {
    let parts: Vec<String> = t.iter().map(|v| v.to_string()).collect();
    format!("({})", parts.join(","))
}

/// The readable report of one analysis.
pub fn report_text(r: &MichellReport) -> String {
    use std::fmt::Write;
    let mut s = text_header(r);
    let _ = writeln!(
        s,
        "\n{:>16} {:>16} {:>12} {:>16} {:>14} {:>6} {:>9}",
        "parent", "child", "length [m]", "q [N/m]", "force [N]", "kind", "governs"
    );
    for m in &r.members {
        member_row(&mut s, m);
    }
    if let Some(t) = r.prestress {
        let _ = writeln!(s, "\nExtra strings (prestress {t} N each):");
        for m in &r.extra_strings {
            member_row(&mut s, m);
        }
    }
    let _ = writeln!(
        s,
        "\nMass: yield {:.6e} kg, yield + buckling {:.6e} kg",
        r.mass_kg.yield_only, r.mass_kg.yield_buckling
    );
    let _ = writeln!(
        s,
        "Normalised yield mass Σ|q|l²/(w0 r0) = {:.9}",
        r.normalized_yield_mass
    );
    let _ = writeln!(s, "Buckling-governed bars: {}", r.buckling_governed.len());
    s
}

/// Geometry, load and counts: the first lines of the readable report.
fn text_header(r: &MichellReport) -> String {
    use std::fmt::Write;
    let p = &r.params;
    let mut s = String::new();
    let geometry = match p.geometry {
        michell3d::Geometry::Planar => "planar (Skelton)".to_string(),
        michell3d::Geometry::Cylindrical { delta } => format!("3-D cylindrical, δ = {delta}"),
        michell3d::Geometry::Spherical { epsilon } => format!("3-D spherical, ε = {epsilon} rad"),
    };
    let _ = writeln!(
        s,
        "Michell truss: {geometry}, complexity q = {}",
        p.complexity
    );
    let _ = writeln!(
        s,
        "  r0 = {} m, β = {:.6} rad ({:.4}°), φ = {:.6} rad ({:.4}°), a = {:.6}, c = {:.6}",
        p.r0,
        p.beta,
        p.beta.to_degrees(),
        p.phi,
        p.phi.to_degrees(),
        p.a(),
        p.c()
    );
    let method = match r.method {
        Method::Recursive => "recursive",
        Method::Global => "global",
    };
    let _ = writeln!(
        s,
        "  tip load w = [{:.6}, {:.6}, {:.6}] N; method {method}; material {}",
        r.load[0], r.load[1], r.load[2], r.material
    );
    let count = |k: MemberKind| r.members.iter().filter(|m| m.kind == k).count();
    let supports = r.nodes.iter().filter(|n| n.support).count();
    let _ = writeln!(
        s,
        "  {} nodes ({} supports), {} members: {} strings, {} bars, {} none",
        r.nodes.len(),
        supports,
        r.members.len(),
        count(MemberKind::String),
        count(MemberKind::Bar),
        count(MemberKind::None)
    );
    s
}

/// The extra strings' check as text lines.
fn extra_text(check: &ExtraStringsCheck) -> String {
    let t = &check.threshold;
    let mut s = match (t.min_extra_prestress, t.critical_member, t.worst_direction) {
        (Some(p), Some(m), Some([az, polar])) => format!(
            "extra strings: min prestress over the nominal region {p:.6} N (member {m}, load \
             azimuth {az:.6} rad, polar {polar:.6} rad)\n"
        ),
        (Some(p), _, _) => {
            format!("extra strings: min prestress over the nominal region {p:.6} N\n")
        }
        _ => format!(
            "extra strings: members {:?} change sign over the nominal region at any prestress\n",
            t.unreachable
        ),
    };
    s += &format!(
        "extra strings: members changing sign over the nominal region: {:?}\n",
        check.sign_changes
    );
    s
}
