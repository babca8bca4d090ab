//! The measured region: what an instruction count covers. The library's drivers run a
//! frame inside it ([`measured_region`]); `tools::callgrind` switches collection on
//! only inside it (`--toggle-collect=*measured_region*`).

/// Everything between entry and exit of this function is counted (`--toggle-collect`
/// matches its symbol, so it must never be inlined).
#[inline(never)]
pub fn measured_region(f: &mut dyn FnMut()) {
    f();
}
