//! The loop shared by the structure-of-arrays warps: one 2-D point in, one
//! 3-D direction out, per index.

/// Points per block of the slice forms that run a warp in more than one
/// loop, keeping its intermediate values in arrays of this length (1 KiB
/// per f32 array, in the first-level cache).
pub(crate) const SOA_BLOCK: usize = 256;

/// The length a structure-of-arrays form runs over: the shortest of its
/// two input and three output slices (every slice form's contract: "the
/// shortest length wins"). Inlined, it is the same five-way minimum each
/// form wrote out.
#[inline(always)]
pub(crate) fn common_len<R>(ux: &[R], uy: &[R], wx: &[R], wy: &[R], wz: &[R]) -> usize {
    ux.len()
        .min(uy.len())
        .min(wx.len())
        .min(wy.len())
        .min(wz.len())
}

/// Writes `f((ux[i], uy[i]))` to `(wx[i], wy[i], wz[i])` for every index of
/// the shortest slice. The slices are cut to one length first, so the loop
/// has no bounds checks and vectorises when `f` inlines branch-free.
#[inline(always)]
pub(crate) fn map2_to3<R: Copy, V2, V3: Into<[R; 3]>>(
    ux: &[R],
    uy: &[R],
    wx: &mut [R],
    wy: &mut [R],
    wz: &mut [R],
    f: impl Fn(V2) -> V3,
) where
    V2: From<[R; 2]>,
{
    let n = common_len(ux, uy, wx, wy, wz);
    let (ux, uy) = (&ux[..n], &uy[..n]);
    let (wx, wy, wz) = (&mut wx[..n], &mut wy[..n], &mut wz[..n]);
    for i in 0..n {
        let [x, y, z] = f(V2::from([ux[i], uy[i]])).into();
        wx[i] = x;
        wy[i] = y;
        wz[i] = z;
    }
}
