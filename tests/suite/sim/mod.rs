//! The simulation against closed forms: contacts, impacts, joints, springs, motors, determinism,
//! and the engine's known gaps with their sizes (src/sim).

mod angle_wrap;
#[cfg(feature = "box2d")]
mod box2d_pin;
#[cfg(feature = "box2d")]
mod box2d_readings;
#[cfg(feature = "box2d")]
mod box2d_refusals;
#[cfg(feature = "box2d")]
mod box2d_window;
mod closed_forms;
mod compound_track;
mod contact_readings;
mod couplings;
mod curved_contact_exact;
mod curved_rough_contact;
mod determinism;
mod eccentric_friction;
mod energy_guard;
mod friction_moving_bodies;
mod impact_approach;
mod impact_planner_joints;
mod impact_twins;
mod impulse_conversions;
mod joint_reaction_particle;
mod joint_sums;
mod known_gaps;
mod load_tables;
mod motor_cable;
mod motor_units;
mod pinned_bar_peg;
mod precision;
mod prescribed_motion;
mod small_oscillations;
mod spinning_contact;
mod springs;
mod substepping_cost;
mod world_fields;
