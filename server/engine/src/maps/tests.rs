use super::*;

static MAP: MapSpec = crate::index_map!("links", segments: "groups", members: PARTICLES, module: "test");

fn u32s(s: &Structure, name: &str) -> Vec<u32> {
    match &s.columns.iter().find(|(a, _)| a.name == name).expect("the attribute").1 {
        Column::U32(v) => v.clone(),
        other => panic!("{name}: {other:?}"),
    }
}

#[test]
fn a_structure_lists_each_segments_members_and_each_members_memberships() {
    // Three groups over five members; member 2 is in every group, member 4 in none.
    let s = MAP.structure(&[vec![0, 2], vec![2, 3, 1], vec![2]], 5);
    assert_eq!(s.memberships, 6);
    assert_eq!(u32s(&s, "links_member"), [0, 2, 2, 3, 1, 2]);
    assert_eq!(u32s(&s, "links_segment"), [0, 0, 1, 1, 1, 2]);
    assert_eq!(u32s(&s, "links_live"), [1; 6]);
    assert_eq!(u32s(&s, "links_start"), [0, 2, 5]);
    assert_eq!(u32s(&s, "links_len"), [2, 3, 1]);
    assert_eq!(u32s(&s, "links_first"), [0, 1, 2, 5, 6]);
    assert_eq!(u32s(&s, "links_count"), [1, 1, 3, 1, 0]);
    // Memberships by member, each member's in membership order.
    assert_eq!(u32s(&s, "links_order"), [0, 4, 1, 2, 5, 3]);
    let spaces: Vec<(&str, &str)> = s.columns.iter().map(|(a, _)| (a.name, a.space)).collect();
    assert!(spaces.contains(&("links_start", "groups")));
    assert!(spaces.contains(&("links_first", "links_by_member")));
    assert_eq!(MAP.live.role, crate::attrs::Role::State, "a member's leaving is saved with the state");
}

#[test]
#[should_panic(expected = "member 7 of segment 1 out of 5")]
fn a_member_out_of_range_is_a_module_error() {
    MAP.structure(&[vec![0], vec![7]], 5);
}
