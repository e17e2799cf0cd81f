//! Every validation error of the structure builder, triggered once, names its culprit.

use tensegrity_core::{
    Bar, CoreError, Material, MemberId, ModelError, StringMember, Structure, Support,
};

fn base() -> tensegrity_core::StructureBuilder {
    Structure::builder().nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
}

fn message(b: tensegrity_core::StructureBuilder) -> (CoreError, String) {
    let e = b.build().unwrap_err();
    let m = e.to_string();
    (e, m)
}

#[test]
fn node_index_out_of_range() {
    let (e, m) = message(base().bar(Bar::new(0, 1)).string(StringMember::new(1, 5)));
    assert!(matches!(
        e,
        CoreError::Model(ModelError::NodeIndexOutOfRange {
            node: 5,
            n_nodes: 3,
            ..
        })
    ));
    assert!(m.contains("string 0") && m.contains('5'), "{m}");
}

#[test]
fn member_joining_a_node_to_itself() {
    let (e, m) = message(base().bar(Bar::new(0, 1)).bar(Bar::new(2, 2)));
    assert_eq!(
        e,
        CoreError::Model(ModelError::SelfLoop {
            member: MemberId::Bar(1),
            node: 2
        })
    );
    assert!(m.contains("bar 1"), "{m}");
}

#[test]
fn duplicate_member_in_either_direction_and_across_kinds() {
    let (e, m) = message(
        base()
            .bar(Bar::new(0, 1))
            .bar(Bar::new(1, 2))
            .string(StringMember::new(1, 0)),
    );
    assert!(matches!(
        e,
        CoreError::Model(ModelError::DuplicateMember {
            member: MemberId::String(0),
            other: MemberId::Bar(0),
            a: 0,
            b: 1
        })
    ));
    assert!(m.contains("string 0") && m.contains("bar 0"), "{m}");
}

#[test]
fn zero_length_member() {
    let (e, m) = message(
        Structure::builder()
            .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
            .bar(Bar::new(0, 1))
            .string(StringMember::new(1, 2)),
    );
    assert!(matches!(
        e,
        CoreError::Model(ModelError::ZeroLengthMember {
            member: MemberId::String(0),
            ..
        })
    ));
    assert!(m.contains("string 0") && m.contains("zero length"), "{m}");
}

#[test]
fn a_member_whose_length_overflows_is_named_as_such_not_as_zero_length() {
    // finite coordinates whose squared distance overflows (found by a catalogue: it used to
    // say "has zero length … length inf m")
    let (e, m) = message(
        Structure::builder()
            .nodes([[0.0, 0.0, 0.0], [1e308, 0.0, 0.0], [-1e308, 0.0, 0.0]])
            .bar(Bar::new(0, 1))
            .string(StringMember::new(1, 2))
            .string(StringMember::new(0, 2)),
    );
    assert!(
        matches!(
            e,
            CoreError::Model(ModelError::MemberLengthOverflow {
                member: MemberId::Bar(0),
                a: 0,
                b: 1,
            })
        ),
        "{m}"
    );
    assert!(m.contains("bar 0") && m.contains("overflows"), "{m}");
    assert!(!m.contains("zero length"), "{m}");
}

#[test]
fn non_finite_coordinate() {
    let (e, m) = message(
        Structure::builder()
            .nodes([[0.0, 0.0, 0.0], [1.0, f64::NAN, 0.0]])
            .bar(Bar::new(0, 1)),
    );
    assert!(matches!(
        e,
        CoreError::Model(ModelError::NonFinite { axis: 'y', .. })
    ));
    assert!(m.contains("node 1"), "{m}");
    let (_, m) = message(
        base()
            .bar(Bar::new(0, 1))
            .bar(Bar::new(1, 2))
            .load(2, [f64::INFINITY, 0.0, 0.0]),
    );
    assert!(m.contains("load 0"), "{m}");
    // two finite loads on one node whose sum overflows: named by the second
    let (_, m) = message(
        base()
            .bar(Bar::new(0, 1))
            .bar(Bar::new(1, 2))
            .load(2, [0.0, -1e308, 0.0])
            .load(1, [0.0, -1e308, 0.0])
            .load(2, [0.0, -1e308, 0.0]),
    );
    assert_eq!(
        m,
        "load 2 (the sum of the loads on node 2): component y is not finite (-inf)"
    );
}

#[test]
fn non_positive_physical_constants() {
    let (e, m) = message(base().bar(Bar::new(0, 1).mass(-1.0)).bar(Bar::new(1, 2)));
    assert!(matches!(
        e,
        CoreError::Model(ModelError::NonPositiveConstant { name: "mass", .. })
    ));
    assert!(m.contains("bar 0") && m.contains("mass"), "{m}");
    let (_, m) = message(
        base()
            .bar(Bar::new(0, 1))
            .string(StringMember::new(1, 2).stiffness(0.0)),
    );
    assert!(m.contains("string 0") && m.contains("stiffness"), "{m}");
    let (_, m) = message(
        base()
            .bar(Bar::new(0, 1))
            .string(StringMember::new(1, 2).rest_length(-0.5)),
    );
    assert!(m.contains("string 0") && m.contains("rest_length"), "{m}");
    let (_, m) = message(
        base()
            .bar(Bar::new(0, 1))
            .string(StringMember::new(1, 2).damping(-2.0)),
    );
    assert!(m.contains("string 0") && m.contains("damping"), "{m}");
    let (_, m) = message(base().bar(Bar::new(0, 1).radius(0.0)).bar(Bar::new(1, 2)));
    assert!(m.contains("bar 0") && m.contains("radius"), "{m}");
    let (_, m) = message(
        base()
            .material("soft", Material::new(1000.0, 0.0, 1e6))
            .bar(Bar::new(0, 1))
            .bar(Bar::new(1, 2)),
    );
    assert!(m.contains("soft") && m.contains("youngs_modulus"), "{m}");
}

#[test]
fn unknown_material() {
    let (e, m) = message(
        base()
            .bar(Bar::new(0, 1))
            .string(StringMember::new(1, 2).material("kevlar")),
    );
    assert!(matches!(
        e,
        CoreError::Model(ModelError::UnknownMaterial { .. })
    ));
    assert!(
        m.contains("string 0") && m.contains("kevlar") && m.contains("steel"),
        "{m}"
    );
}

#[test]
fn isolated_node() {
    let (e, m) = message(base().bar(Bar::new(0, 1)));
    assert_eq!(e, CoreError::Model(ModelError::IsolatedNode { node: 2 }));
    assert!(m.contains("node 2"), "{m}");
}

#[test]
fn supports_out_of_range_duplicated_or_empty() {
    let members = || base().bar(Bar::new(0, 1)).bar(Bar::new(1, 2));
    let (_, m) = message(members().support(Support::pinned(9)));
    assert!(m.contains("support 0") && m.contains('9'), "{m}");
    let (_, m) = message(
        members()
            .support(Support::pinned(1))
            .support(Support::pinned(1)),
    );
    assert!(m.contains("support 1") && m.contains("node 1"), "{m}");
    let (_, m) = message(members().support(Support::directions(0, [false; 3])));
    assert!(m.contains("support 0"), "{m}");
    let (_, m) = message(members().load(7, [0.0, 0.0, 1.0]));
    assert!(m.contains("load 0") && m.contains('7'), "{m}");
}

#[test]
fn velocities_must_match_nodes_and_structures_need_members() {
    let (_, m) = message(
        base()
            .bar(Bar::new(0, 1))
            .bar(Bar::new(1, 2))
            .velocities([[0.0; 3]]),
    );
    assert!(
        m.contains("velocities") && m.contains('3') && m.contains('1'),
        "{m}"
    );
    let (e, _) = message(base());
    assert_eq!(e, CoreError::Model(ModelError::NoMembers));
}
