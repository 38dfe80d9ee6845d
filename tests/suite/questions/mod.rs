//! Questions: what each quantity reads, when an analysis applies, the level library and the
//! levels written from the docs alone (src/questions).

mod analysis_applies;
mod challenge_verdicts;
mod challenges;
mod contact_sag;
mod contacts_in_full;
mod coupling_force;
mod crossing_at_touch;
mod curved_normal_force;
mod damper_work;
mod formula_holds;
mod impact_from_start;
mod impact_lasting;
mod impact_moving_platform;
mod impact_one_reading;
mod ladder_release;
mod leaving_cylinder;
mod library;
mod mistakes;
mod new_quantities;
mod polar_angle;
mod quantity_coverage;
mod reference_applies;
mod reference_rolling;
mod rolling_applies;
mod untuned_levels;
mod virtual_work;
