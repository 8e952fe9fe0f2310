// Kahan's compensated sum (floe-engine `modules::heat::passes::compensated_add`,
// the same operations in the same order): `sum + increment` with `carry`, the
// rounding the sum dropped so far, subtracted first; returns the new sum in x and
// the new carry in y. `zero` must be 0 at run time (the stage's dt.w): the sum's
// bits XOR it, opaque to the shader compiler, which would otherwise simplify
// (t + y) - t - y to 0, and the carry with it.
fn compensated_add(sum: f32, carry: f32, increment: f32, zero: f32) -> vec2<f32> {
    let y = increment - carry;
    let next = bitcast<f32>(bitcast<u32>(sum + y) ^ bitcast<u32>(zero));
    return vec2<f32>(next, (next - sum) - y);
}
