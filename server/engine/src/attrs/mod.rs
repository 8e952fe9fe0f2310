//! The attribute store: every per-particle (or per-wall, per-cell, ...) quantity a
//! scene holds, as a typed column declared once with its name, element type, unit,
//! role and owning module.
//!
//! A module declares its attributes as [`AttrSpec`]s and allocates them through the
//! model builder ([`crate::model::ModelBuilder::attr`]): that is the only way a
//! backend allocates scene data, so a module a scene does not use allocates nothing,
//! and `Backend::allocations` can say what each module costs. The CPU backend keeps
//! the columns here ([`Attrs`]); the GPU backend makes one buffer per attribute from
//! the same specs.
//!
//! Roles decide what the core does with a column without knowing what it means:
//! sorting permutes every [`Role::State`] column of the sorted space, snapshots save
//! them, and the guard checks them for non-finite values; [`Role::Derived`] columns
//! are recomputed from state every step (after a sort or a restore) and never saved.

use crate::math::{Mat3, Quat, Real, Vec3};
use crate::plan::PassSpec;
use std::marker::PhantomData;

mod column;
pub use column::Column;

/// Element type of an attribute.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Elem {
    /// One f32.
    F32,
    /// One u32 (ids, indices, flags).
    U32,
    /// Three f32 (12 bytes on the CPU; a vec4 on the GPU, for alignment).
    Vec3,
    /// Four f32.
    Vec4,
    /// A symmetric 3x3 tensor: xx, yy, zz, xy, xz, yz.
    Sym3,
    /// A 3x3 matrix ([`Mat3`], column-major: three columns of three f32; on the GPU
    /// a WGSL `mat3x3<f32>`, each column padded to a vec4).
    Mat3,
    /// A rotation as a unit quaternion ([`Quat`]: x, y, z, then the scalar part w;
    /// Hamilton's product, a vector rotated as `q v q*`; on the GPU a `vec4<f32>` in
    /// the same order). Zeroed columns hold the identity.
    Quat,
}

impl Elem {
    /// Bytes per element in the CPU store.
    pub fn cpu_bytes(self) -> usize {
        match self {
            Elem::F32 | Elem::U32 => 4,
            Elem::Vec3 => 12,
            Elem::Vec4 | Elem::Quat => 16,
            Elem::Sym3 => 24,
            Elem::Mat3 => 36,
        }
    }

    /// 32-bit words per element in a GPU buffer (vec3 padded to a vec4, a matrix's
    /// columns each to a vec4).
    pub fn gpu_words(self) -> usize {
        match self {
            Elem::F32 | Elem::U32 => 1,
            Elem::Vec3 | Elem::Vec4 | Elem::Quat => 4,
            Elem::Sym3 => 6,
            Elem::Mat3 => 12,
        }
    }

    /// Floats (or u32 words) per element in a snapshot.
    pub fn components(self) -> usize {
        match self {
            Elem::F32 | Elem::U32 => 1,
            Elem::Vec3 => 3,
            Elem::Vec4 | Elem::Quat => 4,
            Elem::Sym3 => 6,
            Elem::Mat3 => 9,
        }
    }

    /// The tag of this type in snapshots.
    pub fn tag(self) -> u8 {
        match self {
            Elem::F32 => 0,
            Elem::U32 => 1,
            Elem::Vec3 => 2,
            Elem::Vec4 => 3,
            Elem::Sym3 => 4,
            Elem::Mat3 => 5,
            Elem::Quat => 6,
        }
    }

    /// Every element type, in tag order.
    pub const ALL: [Elem; 7] = [Elem::F32, Elem::U32, Elem::Vec3, Elem::Vec4, Elem::Sym3, Elem::Mat3, Elem::Quat];
}

/// What the core does with an attribute.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Role {
    /// Evolves from step to step: sorted with its space, saved in snapshots, checked by
    /// the guard.
    State,
    /// Recomputed from state every step; neither sorted nor saved.
    Derived,
    /// Set when the scene is built and never changed (e.g. a wall's temperature);
    /// rebuilt from the scene on restore, not saved.
    Constant,
}

/// An attribute's declaration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AttrSpec {
    /// Name, unique in a scene (`x`, `v`, `rho`, `temperature`).
    pub name: &'static str,
    /// Element type.
    pub elem: Elem,
    /// SI unit of the values (`m/s`); empty when dimensionless.
    pub unit: &'static str,
    /// What the core does with it.
    pub role: Role,
    /// A state attribute added after scenes that hold it were first saved: a
    /// snapshot without it restores it as the scene builds it (zeros for a
    /// rounding carry) instead of being refused.
    pub added_later: bool,
    /// The index space it belongs to (`particles`, `walls`, or one a module declares).
    pub space: &'static str,
    /// The module that declares it (`core`, a scheme's name, or a module's).
    pub module: &'static str,
    /// What it holds.
    pub about: &'static str,
}

/// The particle space: SPH particles, sorted by cell every step.
pub const PARTICLES: &str = "particles";
/// The wall space: boundary particles, fixed.
pub const WALLS: &str = "walls";

/// A Rust type stored in a [`Column`].
pub trait Element: Copy + Send + Sync + std::fmt::Debug + 'static {
    /// Its element type.
    const ELEM: Elem;
    /// The column's values, if it holds this type.
    fn slice(c: &Column) -> Option<&[Self]>;
    /// The column's values, mutable.
    fn slice_mut(c: &mut Column) -> Option<&mut Vec<Self>>;
}

macro_rules! element {
    ($t:ty, $variant:ident) => {
        impl Element for $t {
            const ELEM: Elem = Elem::$variant;
            fn slice(c: &Column) -> Option<&[Self]> {
                match c {
                    Column::$variant(v) => Some(v),
                    _ => None,
                }
            }
            fn slice_mut(c: &mut Column) -> Option<&mut Vec<Self>> {
                match c {
                    Column::$variant(v) => Some(v),
                    _ => None,
                }
            }
        }
    };
}
element!(Real, F32);
element!(u32, U32);
element!(Vec3, Vec3);
element!([f32; 4], Vec4);
element!([f32; 6], Sym3);
element!(Mat3, Mat3);
element!(Quat, Quat);

/// A typed handle on a column, resolved once from the attribute's name.
#[derive(Debug)]
pub struct Attr<T> {
    index: usize,
    _type: PhantomData<T>,
}

impl<T> Clone for Attr<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Attr<T> {}

/// What one attribute takes, for `Backend::allocations`.
#[derive(Debug, Clone, PartialEq)]
pub struct Allocation {
    /// Attribute name.
    pub name: &'static str,
    /// Owning module.
    pub module: &'static str,
    /// Index space.
    pub space: &'static str,
    /// Bytes.
    pub bytes: u64,
}

/// Scratch vectors the permutation swaps in, one per element type.
#[derive(Debug, Default)]
struct Scratch {
    f32: Vec<f32>,
    u32: Vec<u32>,
    vec3: Vec<Vec3>,
    vec4: Vec<[f32; 4]>,
    sym3: Vec<[f32; 6]>,
    mat3: Vec<Mat3>,
    quat: Vec<Quat>,
}

/// The CPU store: one column per declared attribute.
#[derive(Debug, Default)]
pub struct Attrs {
    specs: Vec<&'static AttrSpec>,
    columns: Vec<Column>,
    scratch: Scratch,
    /// The pass running, if one is: it sees only the attributes it declares.
    view: Option<&'static PassSpec>,
}

impl Attrs {
    /// A store holding `columns`, each with its declaration.
    pub fn new(columns: Vec<(&'static AttrSpec, Column)>) -> Self {
        let (specs, columns) = columns.into_iter().unzip();
        Self { specs, columns, scratch: Scratch::default(), view: None }
    }

    /// Narrows the store to what `pass` declares while it runs (`None` after): a
    /// handle to an attribute it neither reads, writes nor accumulates into, or
    /// mutable values of one it only reads, panics naming the pass and the
    /// attribute, so a pass's declaration is the whole of what it touches (the
    /// backend's GPU bindings are checked against the same declaration). The
    /// material index (`material`) is every pass's to read, as on the GPU, where it
    /// rides in each position's w.
    pub fn view(&mut self, pass: Option<&'static PassSpec>) {
        self.view = pass;
    }

    fn check(&self, name: &str, write: bool) {
        let Some(p) = self.view else { return };
        let produces = p.writes.contains(&name) || p.accumulates.contains(&name);
        let reads = produces || p.reads.contains(&name) || name == "material";
        if !(if write { produces } else { reads }) {
            let how = if write { "changes" } else { "uses" };
            let declared = if write { "write or accumulate into" } else { "declare" };
            panic!("pass {} {how} attribute {name}, which it does not {declared} (its PassSpec)", p.name);
        }
    }

    /// The columns with their declarations, the store given up.
    pub fn into_columns(self) -> Vec<(&'static AttrSpec, Column)> {
        self.specs.into_iter().zip(self.columns).collect()
    }

    /// The declarations, in store order.
    pub fn specs(&self) -> &[&'static AttrSpec] {
        &self.specs
    }

    /// Whether the store has an attribute called `name`.
    pub fn has(&self, name: &str) -> bool {
        self.specs.iter().any(|s| s.name == name)
    }

    /// The handle of attribute `name` of type `T`, if the scene has it.
    pub fn find<T: Element>(&self, name: &str) -> Option<Attr<T>> {
        let index = self.specs.iter().position(|s| s.name == name)?;
        self.check(name, false);
        assert_eq!(self.specs[index].elem, T::ELEM, "attribute {name} is not a {:?}", T::ELEM);
        Some(Attr { index, _type: PhantomData })
    }

    /// The handle of attribute `name` of type `T`; panics if the scene lacks it (the
    /// plan checks that every pass's inputs exist before a backend runs it).
    pub fn handle<T: Element>(&self, name: &str) -> Attr<T> {
        self.find(name).unwrap_or_else(|| panic!("no attribute {name} in this scene"))
    }

    /// The values of `a`.
    pub fn get<T: Element>(&self, a: Attr<T>) -> &[T] {
        T::slice(&self.columns[a.index]).expect("handles are typed")
    }

    /// The values of `a`, mutable.
    pub fn get_mut<T: Element>(&mut self, a: Attr<T>) -> &mut Vec<T> {
        self.check(self.specs[a.index].name, true);
        T::slice_mut(&mut self.columns[a.index]).expect("handles are typed")
    }

    /// Takes `a`'s values out (to write them while reading other columns); give them
    /// back with [`Attrs::put`].
    pub fn take<T: Element>(&mut self, a: Attr<T>) -> Vec<T> {
        std::mem::take(self.get_mut(a))
    }

    /// Puts back values taken with [`Attrs::take`].
    pub fn put<T: Element>(&mut self, a: Attr<T>, values: Vec<T>) {
        *self.get_mut(a) = values;
    }

    /// The column called `name`.
    pub fn column(&self, name: &str) -> Option<&Column> {
        self.specs.iter().position(|s| s.name == name).map(|i| &self.columns[i])
    }

    /// Replaces the column called `name` (same type and length expected by the caller).
    pub fn set_column(&mut self, name: &str, column: Column) {
        let i = self.specs.iter().position(|s| s.name == name).unwrap_or_else(|| panic!("no attribute {name}"));
        self.columns[i] = column;
    }

    /// Every column with its declaration.
    pub fn iter(&self) -> impl Iterator<Item = (&'static AttrSpec, &Column)> {
        self.specs.iter().copied().zip(&self.columns)
    }

    /// Applies the permutation `order` to every state column of `space`.
    pub fn permute(&mut self, space: &str, order: &[u32]) {
        for (spec, column) in self.specs.iter().zip(&mut self.columns) {
            if spec.space == space && spec.role == Role::State {
                column.permute(order, &mut self.scratch);
            }
        }
    }

    /// Keeps the elements of `space` where `keep` is true (one flag each), in order,
    /// in every column of the space.
    pub fn retain(&mut self, space: &str, keep: &[bool]) {
        for (spec, column) in self.specs.iter().zip(&mut self.columns) {
            if spec.space == space {
                column.retain(keep);
            }
        }
    }

    /// Resizes every column of `space` to `n` elements (appending zeros, identity
    /// rotations), with room for `capacity` in all.
    pub fn resize(&mut self, space: &str, n: usize, capacity: usize) {
        for (spec, column) in self.specs.iter().zip(&mut self.columns) {
            if spec.space == space {
                column.resize(n, capacity);
            }
        }
    }

    /// What each column takes (the room it holds: a column that grows within its
    /// reserved capacity takes no more).
    pub fn allocations(&self) -> Vec<Allocation> {
        self.iter()
            .map(|(s, c)| Allocation {
                name: s.name,
                module: s.module,
                space: s.space,
                bytes: (c.capacity() * s.elem.cpu_bytes()) as u64,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests;
