//! The generic map passes on the CPU. Each is a value a module declares once
//! (`static COM: SegmentSum<Vec3> = SegmentSum::new(&MAP, "cluster_mx", "cluster_mass_centre")`)
//! and lists among its CPU passes under its own pass name; the GPU has the same
//! four kernels (floe-gpu `maps`).

use super::MapSpec;
use crate::attrs::{Attrs, Element};
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Mat3, Quat, Real, Vec3};
use rayon::prelude::*;
use std::marker::PhantomData;

/// Fewest segments or members a thread takes in the sums: below it the split costs more
/// than it saves.
const PARALLEL_MIN: usize = 1024;

/// An element type that sums (componentwise, in f32).
pub trait Summable: Element + std::ops::Add<Output = Self> {
    /// The sum of nothing.
    const ZERO: Self;
}

impl Summable for Real {
    const ZERO: Self = 0.0;
}
impl Summable for Vec3 {
    const ZERO: Self = Vec3::ZERO;
}
impl Summable for Mat3 {
    const ZERO: Self = Mat3::ZERO;
}
impl Summable for Quat {
    const ZERO: Self = Quat::from_xyzw(0.0, 0.0, 0.0, 0.0);
}

/// The slot of each member id: `slot_of` for particles, the id itself otherwise.
fn slots<'a>(map: &MapSpec, attrs: &'a Attrs) -> Option<&'a [u32]> {
    map.sorted().then(|| attrs.get(attrs.handle::<u32>("slot_of")))
}

fn u32s<'a>(attrs: &'a Attrs, name: &str) -> &'a [u32] {
    attrs.get(attrs.handle::<u32>(name))
}

/// Member → membership: `into[k] = from[slot of member[k]]`. Reads
/// `{map}_member`, `from` (and `slot_of` for particles); writes `into`.
#[derive(Debug)]
pub struct Gather<T> {
    map: &'static MapSpec,
    from: &'static str,
    into: &'static str,
    _t: PhantomData<fn() -> T>,
}

impl<T> Gather<T> {
    /// Member values `from` into membership values `into`.
    pub const fn new(map: &'static MapSpec, from: &'static str, into: &'static str) -> Self {
        Self { map, from, into, _t: PhantomData }
    }
}

impl<T: Element> CpuPass for Gather<T> {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let into = a.handle::<T>(self.into);
        let mut out = a.take(into);
        let (member, from) = (u32s(a, self.map.member.name), a.get(a.handle::<T>(self.from)));
        match slots(self.map, a) {
            Some(slot_of) => out.iter_mut().zip(member).for_each(|(o, &m)| *o = from[slot_of[m as usize] as usize]),
            None => out.iter_mut().zip(member).for_each(|(o, &m)| *o = from[m as usize]),
        }
        a.put(into, out);
    }
}

/// Segment → membership: `into[k] = from[segment[k]]`. Reads `{map}_segment` and
/// `from`; writes `into`.
#[derive(Debug)]
pub struct Spread<T> {
    map: &'static MapSpec,
    from: &'static str,
    into: &'static str,
    _t: PhantomData<fn() -> T>,
}

impl<T> Spread<T> {
    /// Segment values `from` into membership values `into`.
    pub const fn new(map: &'static MapSpec, from: &'static str, into: &'static str) -> Self {
        Self { map, from, into, _t: PhantomData }
    }
}

impl<T: Element> CpuPass for Spread<T> {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let into = a.handle::<T>(self.into);
        let mut out = a.take(into);
        let (segment, from) = (u32s(a, self.map.segment.name), a.get(a.handle::<T>(self.from)));
        out.iter_mut().zip(segment).for_each(|(o, &s)| *o = from[s as usize]);
        a.put(into, out);
    }
}

/// Memberships → segment: `into[s]` is the sum of `values` over segment `s`'s
/// live memberships, in membership order. Reads `{map}_start`, `{map}_len`,
/// `{map}_live` and `values`; writes `into`.
#[derive(Debug)]
pub struct SegmentSum<T> {
    map: &'static MapSpec,
    values: &'static str,
    into: &'static str,
    _t: PhantomData<fn() -> T>,
}

impl<T> SegmentSum<T> {
    /// Sums membership values `values` into segment values `into`.
    pub const fn new(map: &'static MapSpec, values: &'static str, into: &'static str) -> Self {
        Self { map, values, into, _t: PhantomData }
    }
}

impl<T: Summable + Send + Sync> CpuPass for SegmentSum<T> {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let into = a.handle::<T>(self.into);
        let mut out = a.take(into);
        let m = self.map;
        let (start, len, live) = (u32s(a, m.start.name), u32s(a, m.len.name), u32s(a, m.live.name));
        let values = a.get(a.handle::<T>(self.values));
        // Each segment's sum in membership order, segments in parallel: the same sums.
        out.par_iter_mut().enumerate().with_min_len(PARALLEL_MIN).for_each(|(s, o)| {
            let k0 = start[s] as usize;
            *o = (k0..k0 + len[s] as usize).filter(|&k| live[k] != 0).fold(T::ZERO, |acc, k| acc + values[k]);
        });
        a.put(into, out);
    }
}

/// Memberships → member: `into[i]` is the sum of `values` over the live
/// memberships of the member in slot `i`, in membership order. Reads
/// `{map}_first`, `{map}_count`, `{map}_order`, `{map}_live`, `values` (and `id`
/// for particles); writes `into`.
#[derive(Debug)]
pub struct MemberSum<T> {
    map: &'static MapSpec,
    values: &'static str,
    into: &'static str,
    _t: PhantomData<fn() -> T>,
}

impl<T> MemberSum<T> {
    /// Sums membership values `values` into member values `into`.
    pub const fn new(map: &'static MapSpec, values: &'static str, into: &'static str) -> Self {
        Self { map, values, into, _t: PhantomData }
    }
}

impl<T: Summable + Send + Sync> CpuPass for MemberSum<T> {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let into = a.handle::<T>(self.into);
        let mut out = a.take(into);
        let m = self.map;
        let (first, count) = (u32s(a, m.first.name), u32s(a, m.count.name));
        let (order, live) = (u32s(a, m.order.name), u32s(a, m.live.name));
        let ids = m.sorted().then(|| u32s(a, "id"));
        let values = a.get(a.handle::<T>(self.values));
        // Each member's sum in membership order, members in parallel: the same sums.
        out.par_iter_mut().enumerate().with_min_len(PARALLEL_MIN).for_each(|(i, o)| {
            let id = ids.map_or(i, |ids| ids[i] as usize);
            let e0 = first[id] as usize;
            let entries = order[e0..e0 + count[id] as usize].iter().map(|&k| k as usize);
            *o = entries.filter(|&k| live[k] != 0).fold(T::ZERO, |acc, k| acc + values[k]);
        });
        a.put(into, out);
    }
}
