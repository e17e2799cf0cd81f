//! Which method runs, from the method asked for and the data the topology gives.
//!
//! Given data is never ignored: each method uses some of it, and a topology that gives what
//! the method does not use is refused naming the member and the method that would use it.
//!
//! | method | uses | refuses |
//! |---|---|---|
//! | `fdm` | every member's force density | any length (`dr` uses them) |
//! | `adaptive` | the force densities given, as its start (it replaces them) | any length |
//! | `dr` | every member's length, the nodes, the stiffnesses | any force density (`fdm` uses them) |
//!
//! Clusters (`clusters`, a prescribed tension each) are taken by the force density method on
//! held nodes and by dynamic relaxation; the adaptive method, and the force density method on
//! a free-standing topology, refuse them naming `clusters[0]`; a topology of clusters only
//! (no members) takes the force density method.
//!
//! Loads (`loads`, members' `weight`) are the force density method's alone: under `adaptive`
//! or `dr` (asked for, or chosen by the data) they are refused naming the first of them.
//!
//! [`Method::Given`] (the default) takes `fdm` when every member has a force density, `dr`
//! when every member has a length instead and `adaptive` when neither is given; force
//! densities and lengths together, or given on only some members, are refused naming the
//! first member without one. [`Method::Auto`] chooses alike, but takes `adaptive` for force
//! densities on only some members, and falls back to it when the force density method finds
//! no form; it says so ([`Choice::reason`]).

use crate::error::{FormFindError, Result};
use crate::method::Method;
use crate::topology::Topology;

/// The method that runs and why.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Choice {
    /// `Fdm`, `Adaptive` or `Dr`.
    pub method: Method,
    /// Why `auto` chose it (`None` for any other method asked for).
    pub reason: Option<String>,
    /// Whether a failure of the force density method falls back to the adaptive one
    /// (`auto` with every force density given).
    pub fallback: bool,
}

/// The first member with (`with = true`) or without a value in `given`, by name.
fn first(topology: &Topology, given: &[Option<f64>], with: bool) -> Option<String> {
    let k = given.iter().position(|g| g.is_some() == with)?;
    Some(topology.member_name(k))
}

fn refused(item: String, reason: String) -> FormFindError {
    FormFindError::InvalidTopology { item, reason }
}

/// The method that runs for `asked` on `topology` (module docs); the refusal names the
/// member and the method that would use its data.
pub(crate) fn choose(topology: &Topology, asked: Method) -> Result<Choice> {
    let q = topology.given_force_densities();
    let l = topology.given_lengths();
    let with_length = first(topology, &l, true);
    let with_q = first(topology, &q, true);
    let plain = |method| Choice {
        method,
        reason: None,
        fallback: false,
    };
    let chosen = match asked {
        Method::Fdm | Method::Adaptive => match with_length.clone() {
            Some(m) => Err(refused(
                format!("{m}.length"),
                format!(
                    "the {asked} method ignores lengths; dynamic relaxation (`method = dr`) \
                     finds the form from them: use it, or remove the lengths"
                ),
            )),
            None => Ok(plain(asked)),
        },
        Method::Dr => match with_q {
            Some(m) => Err(refused(
                format!("{m}.force_density"),
                "dynamic relaxation ignores force densities; the force density method \
                 (`method = fdm`) finds the form from them: use it, or remove them"
                    .into(),
            )),
            None => Ok(plain(Method::Dr)),
        },
        Method::Given | Method::Auto => by_data(topology, asked, &q, &l),
    };
    chosen
        .and_then(|c| clustered(topology, asked, c))
        .and_then(|c| starts(topology, c, with_length))
        .and_then(|c| loaded(topology, c))
}

/// Clusters (module docs): the force density method on held nodes (the members' force
/// densities given, or no members) and dynamic relaxation take them; the adaptive method, and
/// the force density method on a free-standing topology, refuse them naming `clusters[0]`.
fn clustered(topology: &Topology, asked: Method, c: Choice) -> Result<Choice> {
    if topology.clusters.is_empty() {
        return Ok(c);
    }
    let by_data = matches!(asked, Method::Given | Method::Auto);
    let c = match c.method {
        Method::Adaptive if by_data && topology.n_members() == 0 => Choice {
            method: Method::Fdm,
            reason: (asked == Method::Auto)
                .then(|| "method auto chose fdm: the topology has clusters only".to_string()),
            fallback: false,
        },
        Method::Adaptive => {
            return Err(refused(
                "clusters[0]".into(),
                "the adaptive method finds force densities and takes no clusters (their \
                 tension is given): give the members force densities (the force density \
                 method, with held nodes) or rest lengths (dynamic relaxation)"
                    .into(),
            ))
        }
        // the adaptive method cannot take over: no fallback
        _ => Choice {
            fallback: false,
            ..c
        },
    };
    if c.method == Method::Fdm && topology.fixed.is_empty() {
        return Err(refused(
            "clusters[0]".into(),
            "the force density method takes clusters on held nodes only: a free-standing \
             form is fixed only up to an affine map, which changes the segments' lengths and \
             so their force densities t/l; hold nodes (`[[fixed]]`), or give the members rest \
             lengths (dynamic relaxation)"
                .into(),
        ));
    }
    Ok(c)
}

/// Loads and weights are the force density method's: under another method they are refused
/// by name (the first load, else the first weighted member).
fn loaded(topology: &Topology, c: Choice) -> Result<Choice> {
    if c.method == Method::Fdm || !topology.is_loaded() {
        return Ok(c);
    }
    let item = if topology.loads.is_empty() {
        let k = topology
            .given_weights()
            .iter()
            .position(Option::is_some)
            .unwrap_or(0);
        format!("{}.weight", topology.member_name(k))
    } else {
        "loads[0]".to_string()
    };
    let why = c
        .reason
        .as_deref()
        .map_or(String::new(), |r| format!(" ({r})"));
    Err(refused(
        item,
        format!(
            "the {} method{why} takes no loads; the force density method (`method = fdm`, a \
             force density on every member) finds the loaded form",
            c.method
        ),
    ))
}

/// Dynamic relaxation starts from the topology's nodes: without them the lengths it would
/// use are refused by name.
fn starts(topology: &Topology, c: Choice, with_length: Option<String>) -> Result<Choice> {
    if c.method != Method::Dr || topology.nodes.is_some() {
        return Ok(c);
    }
    let lengths = with_length.map_or(String::new(), |m| format!(" ({m}.length, …)"));
    Err(refused(
        "nodes".into(),
        format!(
            "dynamic relaxation, the method that uses the members' lengths{lengths}, starts \
             from the topology's nodes: give them"
        ),
    ))
}

/// [`Method::Given`] and [`Method::Auto`] (module docs).
fn by_data(
    topology: &Topology,
    asked: Method,
    q: &[Option<f64>],
    l: &[Option<f64>],
) -> Result<Choice> {
    let auto = asked == Method::Auto;
    let choice = |method, reason: &str| Choice {
        method,
        reason: auto.then(|| format!("method auto chose {method}: {reason}")),
        fallback: auto && method == Method::Fdm,
    };
    let (with_q, without_q) = (first(topology, q, true), first(topology, q, false));
    let (with_l, without_l) = (first(topology, l, true), first(topology, l, false));
    if let (Some(mq), Some(ml)) = (&with_q, &with_l) {
        return Err(refused(
            format!("{ml}.length"),
            format!(
                "the topology gives force densities ({mq}) and lengths ({ml}): the force \
                 density method (`method = fdm`) uses the first, dynamic relaxation \
                 (`method = dr`) the second; give one of them"
            ),
        ));
    }
    match (with_q, without_q, with_l, without_l) {
        (Some(_), None, _, _) => Ok(choice(Method::Fdm, "every member has a force density")),
        (Some(mq), Some(m), _, _) if auto => Ok(choice(
            Method::Adaptive,
            &format!(
                "{m} has no force density ({mq} has one): the adaptive method finds them all, \
                 starting from the given ones, which it replaces"
            ),
        )),
        (Some(mq), Some(m), _, _) => Err(refused(
            format!("{m}.force_density"),
            format!(
                "none given, while {mq} has one: the force density method needs every \
                 member's (on the member or its group); give them all, or let the adaptive \
                 method find them (`method = adaptive`, started from the given ones)"
            ),
        )),
        (None, _, Some(_), None) => Ok(choice(Method::Dr, "every member has a length")),
        (None, _, Some(ml), Some(m)) => Err(refused(
            format!("{m}.length"),
            format!(
                "none given, while {ml} has one: dynamic relaxation, the method that uses \
                 lengths, needs every member's (on the member or its group)"
            ),
        )),
        _ => Ok(choice(
            Method::Adaptive,
            "no member has a force density or a length",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::Member;

    fn triangle(q: [Option<f64>; 3], l: [Option<f64>; 3]) -> Topology {
        let member = |k: usize| Member {
            force_density: q[k],
            length: l[k],
            ..Member::new(k, (k + 1) % 3)
        };
        Topology {
            n_nodes: 3,
            nodes: Some(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
            bars: vec![member(0)],
            strings: vec![member(1), member(2)],
            ..Topology::default()
        }
    }

    #[test]
    fn the_data_given_choose_the_method_and_none_is_ignored() {
        let (no, q, l) = (
            [None; 3],
            [Some(-1.0), Some(1.0), Some(1.0)],
            [Some(1.0); 3],
        );
        let chosen = |t: &Topology, m| choose(t, m).map(|c| c.method);
        assert_eq!(chosen(&triangle(q, no), Method::Given), Ok(Method::Fdm));
        assert_eq!(chosen(&triangle(no, l), Method::Given), Ok(Method::Dr));
        assert_eq!(
            chosen(&triangle(no, no), Method::Given),
            Ok(Method::Adaptive)
        );
        // lengths under fdm or adaptive, force densities under dr: refused by member
        let e = choose(&triangle(q, [None, Some(1.0), None]), Method::Fdm).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("strings[0].length: the fdm method ignores lengths"),
            "{e}"
        );
        let e = choose(&triangle(no, l), Method::Adaptive).unwrap_err();
        assert!(
            e.to_string().contains("bars[0].length") && e.to_string().contains("`method = dr`"),
            "{e}"
        );
        let e = choose(&triangle([None, None, Some(1.0)], l), Method::Dr).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("strings[1].force_density: dynamic relaxation ignores"),
            "{e}"
        );
        // both kinds, or one kind on some members only: the member named
        let e = choose(&triangle(q, l), Method::Given)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("bars[0].length: the topology gives force densities (bars[0])"),
            "{e}"
        );
        let some_q = [Some(-1.0), None, Some(1.0)];
        let e = choose(&triangle(some_q, no), Method::Given)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("strings[0].force_density: none given, while bars[0]"),
            "{e}"
        );
        let e = choose(&triangle(no, [Some(1.0), Some(1.0), None]), Method::Auto).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("strings[1].length: none given, while bars[0]"),
            "{e}"
        );
        // lengths without the nodes dynamic relaxation starts from: refused, named
        let mut bare = triangle(no, l);
        bare.nodes = None;
        let e = choose(&bare, Method::Given).unwrap_err().to_string();
        assert!(e.starts_with("nodes: dynamic relaxation, the method that uses the members' lengths (bars[0].length, …)"), "{e}");
        // auto says why, and only it falls back
        let c = choose(&triangle(some_q, no), Method::Auto).unwrap();
        assert_eq!(c.method, Method::Adaptive);
        assert!(c
            .reason
            .unwrap()
            .starts_with("method auto chose adaptive: strings[0] has no force density"));
        let c = choose(&triangle(q, no), Method::Auto).unwrap();
        assert!(c.fallback && c.reason.is_some());
        let c = choose(&triangle(q, no), Method::Given).unwrap();
        assert!(!c.fallback && c.reason.is_none());
    }
}
