//! Checks: pass and fail on theory, the assumptions they verify, windows, twins at other
//! settings, and what never passes (src/checks).

mod absurd_inputs_fail;
mod assumptions;
mod batched;
mod kinetic_energy_ic_moving;
mod pass_and_fail;
mod settings_twins;
mod windows;
