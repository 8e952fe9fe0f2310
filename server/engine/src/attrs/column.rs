//! [`Column`]: one attribute's values in the CPU store, typed by its element.

use super::{Elem, Scratch};
use crate::math::{Mat3, Quat, Vec3};

/// One attribute's values in the CPU store.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// f32 values.
    F32(Vec<f32>),
    /// u32 values.
    U32(Vec<u32>),
    /// 3-vectors.
    Vec3(Vec<Vec3>),
    /// 4-vectors.
    Vec4(Vec<[f32; 4]>),
    /// Symmetric tensors.
    Sym3(Vec<[f32; 6]>),
    /// 3x3 matrices.
    Mat3(Vec<Mat3>),
    /// Rotations.
    Quat(Vec<Quat>),
}

impl Column {
    /// `n` zeros of type `elem`.
    pub fn zeros(elem: Elem, n: usize) -> Self {
        match elem {
            Elem::F32 => Column::F32(vec![0.0; n]),
            Elem::U32 => Column::U32(vec![0; n]),
            Elem::Vec3 => Column::Vec3(vec![Vec3::ZERO; n]),
            Elem::Vec4 => Column::Vec4(vec![[0.0; 4]; n]),
            Elem::Sym3 => Column::Sym3(vec![[0.0; 6]; n]),
            Elem::Mat3 => Column::Mat3(vec![Mat3::ZERO; n]),
            Elem::Quat => Column::Quat(vec![Quat::IDENTITY; n]),
        }
    }

    /// Element type.
    pub fn elem(&self) -> Elem {
        match self {
            Column::F32(_) => Elem::F32,
            Column::U32(_) => Elem::U32,
            Column::Vec3(_) => Elem::Vec3,
            Column::Vec4(_) => Elem::Vec4,
            Column::Sym3(_) => Elem::Sym3,
            Column::Mat3(_) => Elem::Mat3,
            Column::Quat(_) => Elem::Quat,
        }
    }

    /// Elements.
    pub fn len(&self) -> usize {
        match self {
            Column::F32(v) => v.len(),
            Column::U32(v) => v.len(),
            Column::Vec3(v) => v.len(),
            Column::Vec4(v) => v.len(),
            Column::Sym3(v) => v.len(),
            Column::Mat3(v) => v.len(),
            Column::Quat(v) => v.len(),
        }
    }

    /// Whether there are no elements.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Elements it has room for without reallocating.
    pub fn capacity(&self) -> usize {
        match self {
            Column::F32(v) => v.capacity(),
            Column::U32(v) => v.capacity(),
            Column::Vec3(v) => v.capacity(),
            Column::Vec4(v) => v.capacity(),
            Column::Sym3(v) => v.capacity(),
            Column::Mat3(v) => v.capacity(),
            Column::Quat(v) => v.capacity(),
        }
    }

    /// The values as 32-bit words, element by element (f32 by their bits).
    pub fn words(&self) -> Vec<u32> {
        match self {
            Column::F32(v) => v.iter().map(|x| x.to_bits()).collect(),
            Column::U32(v) => v.clone(),
            Column::Vec3(v) => v.iter().flat_map(|x| x.to_array()).map(f32::to_bits).collect(),
            Column::Vec4(v) => v.iter().flatten().map(|x| x.to_bits()).collect(),
            Column::Sym3(v) => v.iter().flatten().map(|x| x.to_bits()).collect(),
            Column::Mat3(v) => v.iter().flat_map(|x| x.to_cols_array()).map(f32::to_bits).collect(),
            Column::Quat(v) => v.iter().flat_map(|x| x.to_array()).map(f32::to_bits).collect(),
        }
    }

    /// A column of `elem` from words as [`Column::words`] writes them; `None` when the
    /// word count is not a whole number of elements.
    pub fn from_words(elem: Elem, words: &[u32]) -> Option<Self> {
        let c = elem.components();
        if !words.len().is_multiple_of(c) {
            return None;
        }
        let f = |w: &[u32]| w.iter().map(|&x| f32::from_bits(x)).collect::<Vec<f32>>();
        Some(match elem {
            Elem::F32 => Column::F32(f(words)),
            Elem::U32 => Column::U32(words.to_vec()),
            Elem::Vec3 => Column::Vec3(words.chunks_exact(3).map(|w| Vec3::from_slice(&f(w))).collect()),
            Elem::Vec4 => {
                Column::Vec4(words.chunks_exact(4).map(|w| std::array::from_fn(|k| f32::from_bits(w[k]))).collect())
            }
            Elem::Sym3 => {
                Column::Sym3(words.chunks_exact(6).map(|w| std::array::from_fn(|k| f32::from_bits(w[k]))).collect())
            }
            Elem::Mat3 => Column::Mat3(words.chunks_exact(9).map(|w| Mat3::from_cols_slice(&f(w))).collect()),
            Elem::Quat => Column::Quat(words.chunks_exact(4).map(|w| Quat::from_slice(&f(w))).collect()),
        })
    }

    /// Whether every value is finite (u32 values always are).
    pub fn all_finite(&self) -> bool {
        self.first_non_finite().is_none()
    }

    /// The first element with a non-finite value.
    pub fn first_non_finite(&self) -> Option<usize> {
        match self {
            Column::F32(v) => v.iter().position(|x| !x.is_finite()),
            Column::U32(_) => None,
            Column::Vec3(v) => v.iter().position(|x| !x.is_finite()),
            Column::Vec4(v) => v.iter().position(|x| x.iter().any(|c| !c.is_finite())),
            Column::Sym3(v) => v.iter().position(|x| x.iter().any(|c| !c.is_finite())),
            Column::Mat3(v) => v.iter().position(|x| !x.is_finite()),
            Column::Quat(v) => v.iter().position(|x| !x.is_finite()),
        }
    }

    /// Keeps the elements where `keep` is true, in order.
    pub(super) fn retain(&mut self, keep: &[bool]) {
        fn go<T>(v: &mut Vec<T>, keep: &[bool]) {
            let mut k = keep.iter();
            v.retain(|_| *k.next().expect("one flag per element"));
        }
        match self {
            Column::F32(v) => go(v, keep),
            Column::U32(v) => go(v, keep),
            Column::Vec3(v) => go(v, keep),
            Column::Vec4(v) => go(v, keep),
            Column::Sym3(v) => go(v, keep),
            Column::Mat3(v) => go(v, keep),
            Column::Quat(v) => go(v, keep),
        }
    }

    /// Resizes to `n` elements, appending zeros (identity rotations), and reserves room
    /// for `capacity` in all.
    pub(super) fn resize(&mut self, n: usize, capacity: usize) {
        fn go<T: Clone>(v: &mut Vec<T>, n: usize, capacity: usize, zero: T) {
            v.reserve_exact(capacity.saturating_sub(v.len()));
            v.shrink_to(capacity);
            v.resize(n, zero);
        }
        match self {
            Column::F32(v) => go(v, n, capacity, 0.0),
            Column::U32(v) => go(v, n, capacity, 0),
            Column::Vec3(v) => go(v, n, capacity, Vec3::ZERO),
            Column::Vec4(v) => go(v, n, capacity, [0.0; 4]),
            Column::Sym3(v) => go(v, n, capacity, [0.0; 6]),
            Column::Mat3(v) => go(v, n, capacity, Mat3::ZERO),
            Column::Quat(v) => go(v, n, capacity, Quat::IDENTITY),
        }
    }

    pub(super) fn permute(&mut self, order: &[u32], scratch: &mut Scratch) {
        use crate::neighbors::permute;
        match self {
            Column::F32(v) => permute(v, &mut scratch.f32, order),
            Column::U32(v) => permute(v, &mut scratch.u32, order),
            Column::Vec3(v) => permute(v, &mut scratch.vec3, order),
            Column::Vec4(v) => permute(v, &mut scratch.vec4, order),
            Column::Sym3(v) => permute(v, &mut scratch.sym3, order),
            Column::Mat3(v) => permute(v, &mut scratch.mat3, order),
            Column::Quat(v) => permute(v, &mut scratch.quat, order),
        }
    }
}
