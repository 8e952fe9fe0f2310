use super::*;

const X: AttrSpec = AttrSpec {
    name: "x",
    elem: Elem::Vec3,
    unit: "m",
    role: Role::State,
    added_later: false,
    space: PARTICLES,
    module: "core",
    about: "",
};
const T: AttrSpec = AttrSpec { name: "t", elem: Elem::F32, unit: "K", ..X };
const R: AttrSpec = AttrSpec { name: "r", elem: Elem::F32, unit: "", role: Role::Derived, ..X };

#[test]
fn permute_moves_state_columns_only() {
    let mut a = Attrs::new(vec![
        (&X, Column::Vec3(vec![Vec3::X, Vec3::Y, Vec3::Z])),
        (&T, Column::F32(vec![1.0, 2.0, 3.0])),
        (&R, Column::F32(vec![7.0, 8.0, 9.0])),
    ]);
    a.permute(PARTICLES, &[2, 0, 1]);
    assert_eq!(a.get(a.handle::<Vec3>("x")), &[Vec3::Z, Vec3::X, Vec3::Y]);
    assert_eq!(a.get(a.handle::<f32>("t")), &[3.0, 1.0, 2.0]);
    assert_eq!(a.get(a.handle::<f32>("r")), &[7.0, 8.0, 9.0], "derived columns stay");
    let bytes: u64 = a.allocations().iter().map(|x| x.bytes).sum();
    assert_eq!(bytes, 3 * 12 + 3 * 4 + 3 * 4);
}

#[test]
fn words_round_trip() {
    let c = Column::Sym3(vec![[1.0, 2.0, 3.0, 4.0, 5.0, f32::NAN]]);
    let back = Column::from_words(Elem::Sym3, &c.words()).unwrap();
    assert_eq!(back.words(), c.words());
    assert_eq!(back.first_non_finite(), Some(0));
    assert!(Column::from_words(Elem::Vec3, &[1, 2]).is_none());
}

/// A pass reading `t` and writing `r`.
static PASS: PassSpec = PassSpec {
    name: "test.pass",
    module: "test",
    stage: crate::plan::Stage::Force,
    reads: &["t"],
    writes: &["r"],
    accumulates: &[],
    tolerance: 0.0,
};

fn viewed() -> Attrs {
    let mut a = Attrs::new(vec![
        (&X, Column::Vec3(vec![Vec3::ZERO; 2])),
        (&T, Column::F32(vec![1.0, 2.0])),
        (&R, Column::F32(vec![0.0; 2])),
    ]);
    a.view(Some(&PASS));
    a
}

#[test]
fn a_running_pass_sees_what_it_declares() {
    let mut a = viewed();
    let (t, r) = (a.handle::<f32>("t"), a.handle::<f32>("r"));
    let doubled: Vec<f32> = a.get(t).iter().map(|v| 2.0 * v).collect();
    a.put(r, doubled);
    assert_eq!(a.get(r), &[2.0, 4.0]);
    a.view(None);
    assert_eq!(a.get(a.handle::<Vec3>("x")).len(), 2, "outside a pass everything is there");
}

#[test]
#[should_panic(expected = "pass test.pass uses attribute x, which it does not declare")]
fn a_pass_using_an_undeclared_attribute_is_stopped() {
    viewed().handle::<Vec3>("x");
}

#[test]
#[should_panic(expected = "pass test.pass changes attribute t, which it does not write or accumulate into")]
fn a_pass_changing_what_it_only_reads_is_stopped() {
    let mut a = viewed();
    let t = a.handle::<f32>("t");
    a.get_mut(t)[0] = 3.0;
}

#[test]
fn matrices_and_rotations_round_trip_and_sort() {
    let m = |k: f32| Mat3::from_cols_array(&std::array::from_fn(|i| k * 10.0 + i as f32));
    let q = |k: f32| Quat::from_rotation_z(k);
    let columns = [Column::Mat3(vec![m(0.0), m(1.0), m(2.0)]), Column::Quat(vec![q(0.0), q(1.0), q(2.0)])];
    for c in columns {
        let elem = c.elem();
        assert_eq!(c.words().len(), 3 * elem.components());
        let back = Column::from_words(elem, &c.words()).unwrap();
        assert_eq!(back, c);
        let tag = Elem::ALL.iter().position(|&e| e == elem).unwrap();
        assert_eq!(tag, elem.tag() as usize, "ALL is in tag order");
        let mut sorted = c.clone();
        sorted.permute(&[2, 0, 1], &mut Scratch::default());
        let third = Column::from_words(elem, &c.words()[2 * elem.components()..]).unwrap();
        assert_eq!(Column::from_words(elem, &sorted.words()[..elem.components()]).unwrap(), third);
    }
    assert_eq!(Column::zeros(Elem::Quat, 2), Column::Quat(vec![Quat::IDENTITY; 2]), "identity, not zeros");
    assert_eq!((Elem::Mat3.cpu_bytes(), Elem::Mat3.gpu_words(), Elem::Quat.gpu_words()), (36, 12, 4));
}
