//! What a run will cost before it starts, in seconds and megabytes, and the budget that refuses
//! a run past it (bad input, exit 2, unless `--allow-long`).
//!
//! The estimate adds measured unit costs over what the level and the overrides say the run
//! will do: rapier calls (one a step, or one a substep where substeps are split:
//! [`Substepping`], or where a ball that can spin touches something at the start), the
//! couplings rigidlab solves after each call, the curved tracks' facets built once and the casts
//! against them that plan short calls, bodies and constraints (joints and potential contact
//! pairs) per substep and per solver iteration, contact pairs made and kept (those at the start
//! and those loose bodies make as they come to rest), the casts against curved tracks (a
//! polyline's points, a second track, a riding ball's arc at fine steps) at every call,
//! questions and checks per step, the windows windowed questions read again each step, and the
//! history a check keeps, and once a run its own start, the facets it builds and the mechanisms
//! its period questions linearize. `check`, `run`, `study stability` and `render --time` all price their
//! run here. The table in docs/cli.md compares the estimate with the measured wall time and
//! peak memory (within 3x on the library and on adversarial levels, tests/budget/).
//!
//! # The unit costs
//!
//! Measured on 2026-11-26 on this 2-core machine (release build, the other cores busy with other
//! builds at times), with `tools/budget_measure.sh` (`/usr/bin/time -v`: wall time and
//! "Maximum resident set size") on the levels `tools/budget_levels.py --calib DIR` writes, each
//! run long enough to take 0.2 to 2 s, and the per-step costs taken as differences between
//! levels that differ in one thing:
//!
//! - [`START_S`]: a one-ball level of 6 steps: 0.01 s.
//! - [`RUN_US`]: the CPU time of a one-step run of each level of `levels/` and `tests/newuser/`
//!   (`BUDGET_DURATION=1e-9 BUDGET_CASES=0 cargo bench --no-default-features --bench budget`,
//!   2026-12-07, load average 4 to 6) less its mean step in a whole run: 0.033 ms in the middle
//!   of the 372 (the world built, the first step's allocations, the report).
//! - [`LINEARIZE_US`], [`LINEARIZE_JOINT_US`]: measured the same way, a question that
//!   linearizes its mechanism (`PendulumPeriod`, `ModePeriod`, `SpringPeriod`,
//!   `EquilibriumAngle`: `analysis::small_oscillations`, numeric Jacobians and SVDs) costs it
//!   once, by the level's joints: 0.04 to 1.7 ms a question without joints (29 levels, 0.76 in
//!   the middle), 4.6 to 5.7 ms with one (12), 2.6 to 13.9 ms with two (11; 10.6 in the
//!   middle), 27 ms with four (the toggle of tests/newuser/statics/n11_08b): 0.7 ms + 5.5 ms a
//!   joint. Unpriced before, these were the lowest ratios of the bench (the toggle 0.20x, the
//!   fast double pendulum n8_04 0.26x, 23 ms of its 31 in the linearization).
//! - [`LINEARIZE_SVD_US`]: that was fitted on 0 to 4 joints; the Hessian of the potential along
//!   the constraints takes 2 d^2 values (d the degrees of freedom), each a projection onto the
//!   constraints by SVDs of the Jacobian of n = 3 columns a body (the SVDs half the time in
//!   `perf`): d^2 n^3. Measured 2026-12-07 on chains of 2 to 30 bars hanging from a pin with one
//!   `PendulumPeriod` (one-step runs as above, load average 5 to 11; `chain` in
//!   tests/suite/runner/budget.rs): 11.1 ms, 61.5 ms, 0.535 s, 23.5 s and 137 s for 2, 5, 10, 20
//!   and 30 bars, priced 0.012 to 0.166 s by the joints alone (30 bars 0.001x); 0.2 us d^2 n^3
//!   more: 1.07x, 0.73x, 1.11x, 0.74x, 0.96x. The mechanism priced is the level's largest set of
//!   dynamic bodies held together by joints ([`Work::mechanism`]).
//! - [`REFERENCE_EVALS_PER_S`], [`REFERENCE_EVALS_PER_SEGMENT`], [`REFERENCE_EVAL_US`],
//!   [`REFERENCE_BODY_EVAL_US`], [`REFERENCE_ROW_EVAL_US`]: a question the reference trajectory
//!   serves (`analysis::reference`: a position, a speed, a reaction read at a time), where its
//!   textbook formula gives no value, integrates the level's equations from the start to its
//!   time, in segments of 0.05 s (0.01 s with rolling contacts) at rtol 1e-10. Measured
//!   2026-12-07 (the CPU time of `Reference::integrate` to each question's time, repeated to 20
//!   ms, on the 38 levels whose runs read it; load average 5 to 7): 690 evaluations a second of
//!   span in segments of 0.05 s, 1800 in segments of 0.01 s (13.5 a segment, 450 a second);
//!   0.19 to 0.21 us an evaluation for a body alone, 0.26 to 0.30 for two, 0.5 to 0.6 with a pin
//!   or a rolling contact, 0.7 to 1.0 with 3 or 4 rows. Unpriced before, these runs of 2 to 7 ms
//!   were priced 0.21x to 0.43x: tests/newuser/statics/n5_12 (5.0 ms of its 7.0 in the
//!   reference), n4_02 (2.8 of 3.7), levels/kinematics/cycloid_rim_point (1.1 of 1.7),
//!   ha_relative_motion_cars_fragment (1.4 of 2.2), free_fall (0.26 of 0.39). A question whose
//!   textbook formula applies does not read it, nor one read after a contact the reference does
//!   not hold: both are known only as the run goes, and priced.
//! - [`CALL_US`]: one ball, 1e6 steps of one rapier call: 1.31 s; a spring split into 100
//!   substeps, 3600 steps (360,000 calls): 0.58 s, 1.6 us a call.
//! - [`BODY_STEP_US`], [`BODY_SUBSTEP_US`]: 1000 free discs, 3600 steps at 1 substep: 0.21 s;
//!   1800 steps at 16 substeps: 0.32 s (and 0.32 s at 8 iterations: iterations cost a body
//!   without constraints nothing).
//! - [`SUBSTEP_US`]: one free ball, 1200 steps of 1000 substeps: 0.11 s.
//! - [`ROW_SUBSTEP_US`], [`ROW_ITERATION_US`] (a joint or a contact pair, per substep and per
//!   substep-iteration): a chain of 200 links, 3600 steps at 8 substeps: 0.34 s at 1 iteration,
//!   0.67 s at 8 (0.008 us a joint-substep-iteration); 1800 steps at 32 substeps: 0.49 s (0.035
//!   us a joint-substep); a pendulum at 1000 substeps, 1200 steps: 0.25 s (0.12 us); a chain of
//!   40 at 96 substeps, 600 steps: 0.24 s (0.09 us). 0.06 us is their middle: the cost of a
//!   joint's substep falls with the joints in the island. Those were taken (2026-11-26) when an
//!   iteration was one biased sweep and every substep ended with rapier's one unbiased sweep.
//!
//!   Since 2026-11-27 an iteration is a biased and an unbiased sweep
//!   (`num_internal_stabilization_iterations = solver_iterations`, sim/build.rs), so the
//!   unbiased sweep moved from the substep to the iteration. Measured again on 2026-11-27 (CPU
//!   time of the best of 3, `--iterations` over the level's, load average 2 to 3): the chain of
//!   200 at 8 substeps, 3600 steps: 0.33 s at 1 iteration (as on 2026-11-26), 0.61 s at 4, 0.98
//!   s at 8, 1.75 s at 16: 0.016 us a joint-substep-iteration; at 32 substeps, 600 steps: 0.17 s
//!   at 1, 0.35 s at 4 (0.016 us). Contacts cost more a sweep: stress/pyramid_20 (590 pairs, 4
//!   substeps) run 3600 steps: 0.72 s at 1 iteration, 1.36 s at 4, 2.12 s at 8 (0.024 us a
//!   pair-substep-iteration); stress/mass_ratio_100 (429 pairs, 32 substeps, 600 steps): 0.40,
//!   0.97, 1.73 s (0.023 us). [`ROW_ITERATION_US`] is their middle, 0.02 us (the chain's
//!   estimate at 8 iterations 1.3x the run, the pyramid's 0.97x, mass_ratio_100's 1.0x; the
//!   biased sweep alone, 0.008 us, gave 0.63x on both contact scenes), and
//!   [`ROW_SUBSTEP_US`] gives up the unbiased sweep it held, 0.068 - 0.02 = 0.048 us, so that
//!   a run at 1 iteration, which does the same sweeps as before, is priced as before.
//! - [`PAIR_CALL_US`]: the library's contact levels (stress/pyramid_20, vertical_stack,
//!   card_house, arch, newtons_cradle), fitted after the terms above, as a price a step; since
//!   2026-12-07 a price a call, as rapier runs its collision detection in every call (a split
//!   step detects collisions once a substep).
//! - Resting pairs: loose bodies (dynamic, in no joint, in no pair at the start) under gravity
//!   in a scene with something fixed come to rest in a heap, with the pairs n discs packed in a
//!   triangle hold, 3 n - 2.83 sqrt(n) (at least n), priced as pairs (`resting_pairs`); loose
//!   balls that can spin roll as they settle, so their steps are priced split. Measured
//!   2026-12-07 (`cargo bench --no-default-features --bench budget`, CPU time of the run's
//!   thread, load average 12 to 16): levels/stress/sand_pile (10,000 grains poured into a bin, no
//!   pair at the start, 28,000 contact manifolds settled) 25.2 s, priced 0.49 s before (0.02x),
//!   12.5 s now (0.50x; 0.37x against 33.4 s in a second run, the CPU time swelling with the
//!   load); the bench's 1,000 grains poured into a bin (3 s) 0.358 s and 0.442 s, priced 0.368
//!   s (1.03x, 0.83x). A pair costs twice as much a step in the 10,000-grain pile as in the 1,000 (1.4
//!   against 0.66 us a pair and a step, the split steps included): see [`PAIR_FAR_COST`].
//! - [`PAIRS_IN_CACHE`], [`PAIR_FAR_COST`]: a pair's rapier data (pair, manifold, solver rows)
//!   take about [`PAIR_KB`], so about 800 pairs fit a core's 2 MB L2 cache; past them each
//!   pair's narrow phase and rows wait on memory. Measured 2026-12-07 by the bench (load average
//!   4 to 9), the factor that would price each scene's pairs past 800 exactly, the other terms
//!   as they are: the bench's 1,000 grains poured into a bin (2,911 pairs settled) 2.2, 10,000
//!   discs on a floor (39,502) 2.05, levels/stress/sand_pile.ron (29,717) 3.7 (its 164 steps
//!   split for spinning grains, unpriced, among them); scenes of 433 and 590 pairs
//!   (stress/mass_ratio_100, pyramid_20) were priced 2.0x and 1.5x with the one price. 2.5:
//!   the grains 1.2x, the discs 1.2x to 1.5x, the sand pile 0.68x (0.29x before).
//! - [`PAIR_MADE_NS`]: rapier makes a contact pair in time proportional to the pairs its bodies
//!   already have (`NarrowPhase::add_pair`, 89% of the run in `perf`): 1000 discs at one point
//!   (499,500 pairs, each body in 999) took 16.7 s for one step, 18.9 s for six.
//! - [`QUESTION_STEP_US`]: 10^4 questions on one ball, 600 steps: 1.02 s, 0.09 s of it loading.
//! - [`CHECK_STEP_US`]: an `impulse_momentum` check over 1e6 steps: 2.07 s against 1.31 s without
//!   (0.76 us a step, its ledger of 48 MB past the caches). Measured again 2026-12-07 by the
//!   bench on copies of levels with and without their checks (the CPU time of the run's thread,
//!   load average 4 to 6): levels/energy/pendulum_energy_fine (8 checks, 3456 steps) 16.2 ms
//!   against 5.9, physical_pendulum (7, 432) 2.10 against 0.79, block_friction_work (3, 480)
//!   1.67 against 1.35, wheel_rolling_ke_ic (5, 252) 0.70 against 0.64, n4_02 (4, 264) 3.42
//!   against 3.30, curve_disc_rolling_in_ring (3, 432) no difference: 0 to 0.43 us a check and
//!   a step, the steps split to read joint impulses for the checks included. 0.3: at 0.8 the
//!   pendulums with 7 and 8 checks were priced 2.4x and 2.7x.
//! - [`VIRTUAL_WORK_JOINT_STEP_US`]: a `virtual_work` check finds the mechanism's virtual
//!   velocities at every step (`analysis::virtual_work::virtual_velocities`, the largest part in
//!   `perf` of levels/virtual-work/zh_slider_crank_static_servo, 2026-12-07). Fitted 2026-12-07 on
//!   the bench's runs (load average 5 to 11) as the CPU time past the other terms: that level (2
//!   checks, 8 joints, 500 steps) 15 us a step, 0.96 us a check-joint; the four-bar held by a
//!   servo tests/newuser/statics/i14_02 (1, 4) 6.5 us a step, 1.6 us a check-joint: 1.0 (priced
//!   0.37x and 0.53x without; the other 9 levels with the check 0.70x to 1.51x, 0.97x to 1.59x
//!   with it).
//! - [`BASE_MB`] and the per-item memory: the peak of a one-ball run (31.3 MB); 1000 discs at
//!   one point 1282 MB, 300 at one point 124 MB (2.1 to 2.5 KB a pair); 10^4 questions 66.5 MB
//!   (3.4 KB each); 1000 free bodies 32.6 MB; the `impulse_momentum` check over 1e6 steps
//!   77.1 MB (48 bytes a step, as `ImpulseMomentumLedger` stores them).
//! - [`FACET_US`]: a curved track's facets (an `Arc`'s, a `Polyline`'s points) are built once,
//!   with the tree parry searches them by; a ball on an `Arc` touches its circle
//!   (sim/arc_track.rs), and any other shape finds its facets through that tree, so a call does
//!   not pay for each facet. Measured 2026-12-06 (the thread's CPU time of 20 runs in one
//!   process, `runner::budget::measure_estimates` in tests/suite/runner/budget.rs): a puck in a
//!   ring of 7025 facets over 1000 steps (tests/newuser/curved/n13_05) 10.3 ms, where the other
//!   terms price 2.5 ms: 1.1 us a facet. Measured again 2026-12-07 as [`RUN_US`] is, from the
//!   one-step runs of the 56 levels with facets and no linearizing question: 0.30 to 0.43 us a
//!   facet, 0.31 in the middle, so 0.32 (1.1 priced the ring's rolling disc 2.60x, the hoop in a
//!   ring n9_06 2.74x: the 10.3 ms had held the run's other costs). From 2026-12-06 to then each call was priced 0.04 us a
//!   facet (`FACET_CALL_US`, measured before the arc's exact contact: n7_05, a puck in that ring,
//!   1.20 s then): after it n13_05 was priced 0.29 s for 10 ms, n7_05 1.1 s for 18 ms.
//! - [`COUPLING_CALL_US`]: a coupling (a cable, a belt, gears: sim/couplings.rs) is solved by
//!   rigidlab after every rapier call, in sweeps over its terms' coordinates (an angle is an
//!   atan2). Measured 2026-12-06 as above, the run's time past the other terms over its calls
//!   and couplings: levels/kinematics/ha_double_pulley_cable (1 coupling, 16,800 calls) 0.142 s
//!   against 0.028 s, 6.8 us a coupling-call; tests/newuser/linkages/n8_10 (1, 3000 calls) 28 ms
//!   against 5 ms, 7.7 us; levels/kinetics/classic_atwood_massive_pulley (2, 1152 calls) 17.8
//!   ms against 2.3 ms, 6.7 us. Unpriced before, these ran 5x to 8x their estimate.
//!   Those cables all run over a pulley or a drum: a term in its angle. [`COUPLING_CALL_US`],
//!   [`COUPLING_ANGLE_CALL_US`]: a cable between bodies' x and y, measured 2026-12-07 by the bench
//!   the same way: levels/kinetics/ha_blocks_A_B_pulley_C 1.9 us a call,
//!   ha_hoist_power_efficiency 2.2, levels/kinematics/ha_collars_pulley_dependent_motion (three
//!   terms) 2.1, ha_three_block_dependent_motion 3.0, priced 1.7x to 2.4x at 7: 2.5 us a
//!   coupling, and 4.5 more for one with a term in an angle.
//! - A spinning ball in contact: rigidlab splits a step into several calls where a dynamic
//!   ball's turn over a call would disturb its contact (sim/contact_points.rs, `spin_calls`), a
//!   choice made during the run. The estimate makes it before: a dynamic `Circle` that may turn
//!   (not `lock_rotation`; friction on, or started turning) in a contact pair at the start, with
//!   more than one substep, is priced at `substeps` calls a step where a question reads a
//!   contact's start, end or slip (the strict rule, which splits early), else at one call.
//!   Measured 2026-12-06 under the rule of then (every step split while a ball spun in
//!   contact): levels/kinetics/classic_rolling_disc split 248 of its 252 steps,
//!   tests/newuser/curved/n7_02 (a ball rolling in a bowl) 588 of 624; under the rule of
//!   2026-12-07, 41 (into 2 calls) and none. [`SPIN_SPLIT_SHARE`]: where the strict rule prices
//!   a level's steps split for a spinning ball alone, the bench (2026-12-07, the calls each
//!   report counts) found 3% to 99% of their steps split, 40% to 50% in the middle (the balls
//!   on rough floors n4_09, n4_10 3%, the wheels at a curb 24%, priced 2.2x to 2.6x at every
//!   step split): priced half of them split.
//! - [`JOINTS_IN_LANES`], [`JOINT_LANE_COST`]: measured 2026-12-07 by the bench on the nets of
//!   levels/stress/generate.py's `joint_grid` at n = 6, 10, 15, 22 and 30 (600 steps of 16
//!   substeps; the joints' rows 90% of their price): 55 and 174 joints priced 0.94x and 0.89x,
//!   414, 918 and 1734 joints 2.21x, 2.32x and 2.30x, where a joint's rows cost 0.35x (rapier's
//!   staged solver runs a color of 64 joints or more in its SIMD lanes); the chains of 40 to 81
//!   joints (stress/stretched_chain, ball_and_chain, bridge_80) 0.87x to 0.94x.
//! - A smooth ball on an arc: rigidlab splits a step into one-substep calls while a smooth
//!   dynamic ball rides a fixed `Arc`'s circle (sim/arc_split.rs). The estimate prices it so
//!   from the start for a smooth dynamic `Circle` in a contact pair with a fixed smooth `Arc`,
//!   with more than one substep. Measured 2026-12-07: tests/newuser/curved/n14_02 (a puck down a
//!   ramp arc into a loop, 1/4800 s, 4 substeps) 0.34 s before, 1.09 s split, every step split.
//! - [`MOTOR_WINDOW_US`], [`CONTACT_WINDOW_US`], [`JOINT_WINDOW_US`]: a question with a
//!   `window` reads its window's snapshots again at every step (questions/probe.rs), so it costs
//!   steps x window / dt (issue 45: the slotted arm at dt 1e-6, priced 0.61 s, ran past 226 s).
//!   Measured 2026-12-07 (CPU time of `check --dt 2e-5 --no-advice`, a copy of the level cut
//!   short, with its window and with `window: 0.0`): levels/virtual-work/zh_slider_slotted_arm
//!   (`MotorTorque`, 10 ms; 0.04 s) 1.43 s against 0.03 s, 1.0e6 snapshots read: 1.4 us each
//!   (1.5 us at 1e-5, 1.7 us at 5e-6), the power balance's analysis at each; tests/newuser/curved/
//!   n14_14 (`ContactForceFrom`, 10 ms; 0.3 s) 1.80 s against 0.17 s, 7.5e6: 0.22 us;
//!   levels/kinematics/ha_polar_arm_collar (`JointReaction`, 20 ms; 0.3 s) 0.31 s against 0.22
//!   s, 1.5e7: 0.006 us. A question read at a `Time` stops there; any other is priced to the end.
//!   Measured again 2026-12-07 by the bench (the CPU time of the run's thread, which leaves out
//!   the process and the report that `check`'s figures held): the slotted arm at dt 2e-5, 0.04
//!   s, 0.626 s, 0.6 us a snapshot (1.4 priced it 2.26x). A snapshot costs more as the window
//!   grows (1.4, 1.5 and 1.7 us at 2e-5, 1e-5 and 5e-6 with `check`: 1.2x over a window 4x
//!   as long), so [`MOTOR_WINDOW_US`] is 1.0: the arm at 2e-5 1.5x, and at dt 1e-6 (10,001
//!   snapshots a step) priced about 800 s, refused. n13_05 at dt 1e-5, 0.05 s, 0.337 s with its
//!   casts (below), which 0.22 us a snapshot priced 2.65x: [`CONTACT_WINDOW_US`] 0.1 us, fitted
//!   there (1.7x).
//! - [`TRACK_CAST_US`], [`TRACK_CAST_CALL_S`]: where the calls are cut at impacts
//!   (sim/impacts.rs, scenes of at most 64 moving bodies), every pair that closes faster than
//!   2 g h + 1 mm/s (h the call) and is more than 10 um apart is cast against the other before
//!   the call, and a cast against a curved track's facets walks the facets' tree. At coarse steps
//!   that is rare; at fine ones every call. Measured 2026-12-07 (CPU time over the calls the
//!   report counts, `check --dt` of a copy cut to 20,000 steps or 0.3 s):
//!   levels/kinetics/curve_disc_rolling_in_ring 2.9, 3.1, 2.7 and 2.7 us a call at dt 4.2e-4,
//!   1e-4, 4.2e-5 and 1e-5, then 6.4 us at 4.2e-6, 31 us at 2e-6 and 35 us at 1e-6 (its calls
//!   dt / 4, split for the disc's spin); tests/newuser/curved/n13_05 (a puck in a ring) 30 us at
//!   1e-5 (calls of 2.5 us). Priced 30 us a call for each pair of a moving body and a curved
//!   track at the start, from calls of 2.5 us down. Measured again 2026-12-07 by the bench: the
//!   ring's rolling disc at dt 2e-6 2.6 us a call (its casts gone since), priced 12.7x, and at
//!   1e-5 19.3x; the puck at 1e-5 17 us a call. Since then only a smooth ball riding a smooth
//!   `Arc` (the puck) is priced a cast, 15 us a call from calls of 2.5 us down: the ring's disc
//!   0.93x at 2e-6 and 1.48x at 1e-5, the puck 1.68x (its window included). The ring at dt
//!   4.2e-8 is priced its 1.7e8 calls alone, about 430 s, and accepted. Measured again
//!   2026-12-07 by the bench (load average 4 to 6): the ring's disc at 2e-6 (one call a step,
//!   none split) 10.0 to 10.7 us a step, priced 2.5 (0.39x), and `perf` of that run finds the
//!   planner's nonlinear casts (parry's `nonlinear_shape_cast`, its `closest_point`) the largest
//!   part; the puck at 1e-5, 0.326 s, priced 1.80x with 15 us. So every dynamic ball on a fixed
//!   `Arc` at the start is priced a cast from calls of 2.5 us down, 10 us: the disc 1.4x, the
//!   puck 1.5x; the ring at 4.2e-8 is priced about 585 s, just within the budget. Its calls
//!   there, measured the same evening on copies cut to 0.004 s and 0.04 s (0.65 s and 2.97 s of
//!   CPU, the start dearer than the rest), cost at most 1.7 us: the whole run at most 134 s,
//!   so the price is 4.4x or more over, on the safe side (issue 45's 11 hours are gone with the
//!   exact contact).
//! - [`POLYLINE_FACET_CALL_US`]: a body on a `Polyline` is queried and cast against the
//!   polyline's points at every call (sim/impacts.rs; an `Arc` is met by its circle). Measured
//!   2026-12-07 by the bench (the CPU time over the calls the report counts, less the other
//!   terms): tests/newuser/curved/n12_01a and n12_01b (a loop of 6150 points) 195 and 187 us a
//!   call, n9_05 (a ramp of 4002) 209, n9_07 (two pucks, cycloids of 4001 each) 131 a puck: 0.030
//!   to 0.052 us a point and a call, priced 0.035. Priced 0.02x to 0.05x before.
//! - [`OTHER_TRACK_CALL_US`]: a body on a curved track meets the scene's other curved tracks (a
//!   loop's circle after its ramp), and is queried and cast against each as it comes near.
//!   Measured 2026-12-07 as above: the loops of two `Arc`s (levels/energy/curve_loop_the_loop and
//!   its rolling twin, levels/challenges/loop_least_height, tests/newuser/curved/n7_01, n14_01,
//!   n14_02, n14_03, n14_23) 12 to 19 us a call, priced 0.09x to 0.3x before; a ramp, a floor and
//!   a loop apart (n15_01a-c) 2.4 us. 9 us, between the two: the loops 0.57x to 0.76x, the
//!   ramp-floor-loops 1.78x to 1.84x.
//! - [`RENDER_S`], [`RENDER_MB`]: `render` of free_fall at 0.5 s (Vulkan, lavapipe): 0.81 s, 222 MB.

use crate::level::shape as shapes;
use crate::level::{
    BodyKind, CheckKind, Coordinate, Effect, Level, LevelError, Quantity, QuantityFamily, When,
};
use crate::sim::{Options, Settings, Substepping};
use once::{largest_mechanism, reference_us};

mod once;
use std::path::Path;

/// The time budget of one run, s: past it a run is refused unless `--allow-long`.
pub const TIME_BUDGET_S: f64 = 600.0;
/// The memory budget of one run, MB (2^20 bytes): past it a run is refused unless `--allow-long`.
pub const MEMORY_BUDGET_MB: f64 = 4096.0;

/// The process's start and the level's load, s.
pub const START_S: f64 = 0.01;
/// A run's own start, once: the world built, the first step's allocations, the report, us.
pub const RUN_US: f64 = 30.0;
/// A question that linearizes its mechanism about equilibrium (`PendulumPeriod`, `ModePeriod`,
/// `SpringPeriod`, `EquilibriumAngle`: `analysis::small_oscillations`), once, us.
pub const LINEARIZE_US: f64 = 700.0;
/// The same, per joint of the level: the constraints' numeric Jacobians and their SVDs, us.
pub const LINEARIZE_JOINT_US: f64 = 5500.0;
/// The same, per d^2 n^3 of the largest jointed mechanism (d its degrees of freedom, n its 3
/// coordinates a body): the potential's Hessian along the constraints takes 2 d^2 of its values,
/// each a projection onto the constraints by SVDs of the n-column Jacobian, us.
pub const LINEARIZE_SVD_US: f64 = 0.2;
/// The contact pairs whose rapier data (pair, manifold, solver rows: [`PAIR_KB`] each) fit a
/// core's 2 MB L2 cache: past them a pair's narrow phase and rows wait on memory.
pub const PAIRS_IN_CACHE: f64 = 800.0;
/// A pair past [`PAIRS_IN_CACHE`] against one within, in every term a pair is priced in.
pub const PAIR_FAR_COST: f64 = 2.5;
/// Joints from which rapier's solver runs every joint color in its SIMD lanes: rapier 0.36's
/// staged island solver sends a color (joints sharing no body) of at least 64 joints
/// (`JOINT_BATCH` 16 x 8 reference workers / 2) to its lanes and a smaller one to a serial
/// tail; a 2D scene's joints take 2 (a chain) to 4 (a net) colors.
pub const JOINTS_IN_LANES: usize = 256;
/// A joint's rows in the lanes against in the serial tail.
pub const JOINT_LANE_COST: f64 = 0.35;
/// Of the steps a spinning ball in contact may split (priced at `substeps` calls: the strict
/// rule where a question reads a contact's start, end or slip), the share that the run splits.
pub const SPIN_SPLIT_SHARE: f64 = 0.5;
/// One rapier call (`PhysicsPipeline::step`) with its reading into the snapshot, us.
pub const CALL_US: f64 = 1.3;
/// One body read into a step's snapshot and its step's bookkeeping, us.
pub const BODY_STEP_US: f64 = 0.05;
/// One substep of a rapier call, whatever it holds, us.
pub const SUBSTEP_US: f64 = 0.08;
/// One body integrated in one substep, us.
pub const BODY_SUBSTEP_US: f64 = 0.008;
/// One constraint (a joint or a potential contact pair) prepared in one substep, us.
pub const ROW_SUBSTEP_US: f64 = 0.048;
/// One constraint solved in one solver iteration of one substep, us: the iteration's biased
/// sweep and its unbiased (stabilization) sweep, both run `solver_iterations` times a substep
/// since 2026-11-27 (sim/build.rs).
pub const ROW_ITERATION_US: f64 = 0.02;
/// One potential contact pair in the narrow phase, per rapier call, us (each call runs rapier's
/// collision detection).
pub const PAIR_CALL_US: f64 = 0.1;
/// Making one contact pair, per pair its two bodies already have, ns (paid once, when the pairs
/// of bodies that overlap at the start are made).
pub const PAIR_MADE_NS: f64 = 17.0;
/// One facet of a curved track (an `Arc`'s facets, a `Polyline`'s points), built once with its
/// search tree, us.
pub const FACET_US: f64 = 0.32;
/// One coupling solved after one rapier call, us (a cable between bodies' x and y).
pub const COUPLING_CALL_US: f64 = 2.5;
/// A coupling with a term in a body's angle (a cable over a massive pulley or a drum, gears),
/// more than [`COUPLING_CALL_US`], per call, us: its angle is read as an atan2 and set as a
/// turned pose about the mass centre in every sweep.
pub const COUPLING_ANGLE_CALL_US: f64 = 4.5;
/// The reference trajectory's integration (`analysis::reference`), right-hand-side evaluations
/// per second of the span integrated, beyond those each segment's restart costs.
pub const REFERENCE_EVALS_PER_S: f64 = 450.0;
/// The same, evaluations each segment's restart costs (the integrator's first step and its
/// step-size guess, after each projection onto the constraints).
pub const REFERENCE_EVALS_PER_SEGMENT: f64 = 13.5;
/// One evaluation of the reference's right-hand side, us: its start, ...
pub const REFERENCE_EVAL_US: f64 = 0.1;
/// ... per dynamic body it integrates, ...
pub const REFERENCE_BODY_EVAL_US: f64 = 0.1;
/// ... and per constraint row it solves (the Schur complement's Cholesky among them).
pub const REFERENCE_ROW_EVAL_US: f64 = 0.15;
/// One question watching one step, us.
pub const QUESTION_STEP_US: f64 = 0.15;
/// One snapshot of a `MotorTorque` question's averaging window, read at one step, us: the window
/// is summed again at every step, with the power balance's analysis at each of its snapshots.
pub const MOTOR_WINDOW_US: f64 = 1.0;
/// One snapshot of a `ContactForceFrom` question's window, read at one step, us.
pub const CONTACT_WINDOW_US: f64 = 0.1;
/// One snapshot of a `JointReaction` question's window, read at one step, us.
pub const JOINT_WINDOW_US: f64 = 0.006;
/// One nonlinear shape cast of a moving body against a curved track's facets, planning an
/// impact cut before a call (sim/impacts.rs), us.
pub const TRACK_CAST_US: f64 = 10.0;
/// Calls at most this long, s, cast a body against the curved track it rides at every call.
pub const TRACK_CAST_CALL_S: f64 = 2.5e-6;
/// One point of a `Polyline` a moving body is on, per rapier call, us: the impact planner's
/// query and cast against the polyline walk its points.
pub const POLYLINE_FACET_CALL_US: f64 = 0.035;
/// A curved track other than the one a moving body starts on (a loop's circle after its ramp),
/// per rapier call, us: the planner's query and cast against it as the body comes near.
pub const OTHER_TRACK_CALL_US: f64 = 9.0;
/// One check observing one step, us.
pub const CHECK_STEP_US: f64 = 0.3;
/// A `virtual_work` check, beyond [`CHECK_STEP_US`], per joint of the level and per step, us:
/// it finds the mechanism's virtual velocities at every step (`analysis::virtual_work`).
pub const VIRTUAL_WORK_JOINT_STEP_US: f64 = 1.0;
/// The engine's part of a step in f64 against f32 (rapier2d-f64 against rapier2d: 1.2x to 1.3x
/// over the library, docs/accuracy.md; `study::advice::F64_COST`).
pub const F64_COST: f64 = 1.25;
/// The process itself: the binary and the allocator's start, MB.
pub const BASE_MB: f64 = 32.0;
/// A body, KB.
pub const BODY_KB: f64 = 1.5;
/// A joint, KB.
pub const JOINT_KB: f64 = 4.0;
/// A potential contact pair (rapier's pair, manifold and solver rows), KB.
pub const PAIR_KB: f64 = 2.5;
/// A question, KB.
pub const QUESTION_KB: f64 = 3.4;
/// `render`: the renderer's start, its first frame and the PNG, s and MB.
pub const RENDER_S: f64 = 0.8;
pub const RENDER_MB: f64 = 200.0;

/// Contact pairs past this many are not counted further (the memory alone is past any budget).
const PAIRS_COUNTED: f64 = 1e7;

/// Which command runs the level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mode {
    /// `check`, `study stability`: the checks and questions observe each step.
    Check,
    /// `run`: also writes the snapshots as CSV when asked.
    Run,
    /// `render --time T`: the window's physics to T, then one frame.
    Render,
}

/// What a run will do, counted from the level and the overrides before it starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Work {
    /// Steps (f64, so that `--dt 1e-300` gives a number, not an overflow).
    pub steps: f64,
    pub substeps: usize,
    pub iterations: usize,
    /// rapier calls a step: 1, or `substeps` where substeps are split (planned, or for a ball
    /// that can spin in contact).
    pub calls_per_step: usize,
    /// Of the steps priced at `calls_per_step` calls, the share the run is expected to split:
    /// 1, or [`SPIN_SPLIT_SHARE`] where a spinning ball in contact is the only reason
    /// ([`Work::calls`]).
    pub split_share: f64,
    pub bodies: usize,
    pub joints: usize,
    /// Pairs of colliding bodies whose boxes overlap (within 1 cm) at the start, and those the
    /// loose bodies make as they come to rest ([`Work::resting_pairs`]).
    pub pairs: f64,
    /// Of [`Work::pairs`], those made as loose bodies come to rest (dynamic bodies in no joint
    /// and no pair at the start, under gravity, in a scene with something fixed), counted as a
    /// heap of discs holds them (3 n - 2.83 sqrt(n) for n loose bodies, `resting_pairs`).
    pub resting_pairs: f64,
    /// Sum over those pairs of the pairs their two bodies are in (what making them costs).
    pub pair_degrees: f64,
    /// The facets of the level's curved tracks, built once.
    pub facets: f64,
    /// Couplings rigidlab solves after every rapier call (0 without joints).
    pub couplings: usize,
    /// Of them, those with a term in a body's angle ([`COUPLING_ANGLE_CALL_US`]).
    pub turning_couplings: usize,
    pub questions: usize,
    /// Questions that linearize their mechanism once ([`LINEARIZE_US`]).
    pub linearizations: usize,
    /// Of the level's largest mechanism of dynamic bodies held by joints (or of one body): its
    /// coordinates n (3 a body) and its degrees of freedom d (n less its joints' rows, at least
    /// 1), which price a linearization beyond its joints ([`LINEARIZE_SVD_US`]).
    pub mechanism: (usize, usize),
    /// The reference trajectory's integrations, us: every question a reference trajectory can
    /// serve (`questions::level_facts::served_by_reference`) read at a time integrates it from
    /// the start to that time (`runner/budget/once.rs`).
    pub reference_us: f64,
    pub checks: usize,
    /// Over the `virtual_work` checks, the level's joints ([`VIRTUAL_WORK_JOINT_STEP_US`]).
    pub virtual_work_joints: usize,
    /// Bytes the checks keep per step (their histories).
    pub history_bytes_per_step: f64,
    /// The engine in f64 (rapier2d-f64), whose steps cost [`F64_COST`] times f32's.
    pub f64: bool,
    /// The step, s.
    pub dt: f64,
    /// The snapshots the windowed questions read a step, over the run (see [`Windows`]).
    pub windows: Windows,
    /// Pairs of a dynamic ball and a fixed `Arc` at the start (a puck riding it, a disc rolling
    /// on it), when the run cuts its calls at impacts (sim/impacts.rs): each costs a shape cast
    /// against the track a call once calls are short ([`TRACK_CAST_CALL_S`]).
    pub track_pairs: f64,
    /// Over the pairs of a moving body and a `Polyline` at the start, the polyline's points, when
    /// the run cuts its calls at impacts: each call walks them ([`POLYLINE_FACET_CALL_US`]).
    pub polyline_facets: f64,
    /// Over the moving bodies on a curved track at the start, the scene's other curved tracks,
    /// when the run cuts its calls at impacts ([`OTHER_TRACK_CALL_US`]).
    pub other_tracks: f64,
}

/// The snapshots windowed questions read a step, by family, averaged over the run's steps: a
/// question with a `window` of w s at a step dt reads 2 round(w / 2 dt) + 1 snapshots at every
/// step until it is read for good (its `Time`; to the end otherwise), so its price grows as
/// steps x w / dt: the square of the steps.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Windows {
    /// The questions with a window past one step each side.
    pub questions: usize,
    pub motor: f64,
    pub contact: f64,
    pub joint: f64,
}

impl Windows {
    fn of(level: &Level, dt: f64) -> Windows {
        let mut w = Windows::default();
        let duration = level.world.duration.max(dt);
        for q in &level.questions {
            let window = q.quantity.averaging_window();
            // As QuestionProbe counts them: lag steps each side, a window only past one.
            let lag = (0.5 * window / dt).round().max(1.0);
            if lag <= 1.0 {
                continue;
            }
            let active = match q.at {
                When::Time(at) => ((at + 0.5 * window) / duration).clamp(0.0, 1.0),
                _ => 1.0,
            };
            let samples = (2.0 * lag + 1.0) * active;
            w.questions += 1;
            match q.quantity {
                Quantity::MotorTorque { .. } => w.motor += samples,
                Quantity::ContactForceFrom { .. } => w.contact += samples,
                _ => w.joint += samples,
            }
        }
        w
    }

    /// Their price a step, us.
    pub fn step_us(&self) -> f64 {
        self.motor * MOTOR_WINDOW_US
            + self.contact * CONTACT_WINDOW_US
            + self.joint * JOINT_WINDOW_US
    }
}

/// The estimate of one run: its [`Work`] priced with the unit costs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    pub work: Work,
    pub mode: Mode,
    pub seconds: f64,
    pub megabytes: f64,
}

impl Work {
    /// The work of running `level` with the command line's overrides for `steps` steps (None:
    /// world.duration / dt).
    pub fn of(level: &Level, opts: &Options, steps: Option<f64>) -> Work {
        let precision = opts.precision.unwrap_or(level.world.precision);
        let set = Settings::resolve(level, opts, precision);
        let steps = steps.unwrap_or_else(|| {
            // As Simulation::total_steps counts them.
            (level.world.duration / opts.dt.unwrap_or(level.world.dt))
                .round()
                .max(1.0)
        });
        let contacts = if set.effects.has(Effect::Contacts) {
            contact_pairs(
                level,
                set.effects.has(Effect::Friction),
                set.effects.has(Effect::Gravity),
            )
        } else {
            Pairs::default()
        };
        let history_bytes_per_step = level
            .checks
            .iter()
            .map(|c| match c.kind {
                // ImpulseMomentumLedger: (t, G, J, |G|) 48 bytes, and (H, M, |H|) 24 more about a point.
                CheckKind::ImpulseMomentum => {
                    if c.point.is_some() {
                        72.0
                    } else {
                        48.0
                    }
                }
                // WorkEnergy: (t, E - E_theory) a step, for the drift rate.
                CheckKind::WorkEnergy => 16.0,
                _ => 0.0,
            })
            .sum();
        // Every step split: planned, joint impulses reconstructed but for blows (measured
        // 2026-12-07: its smoothness guard kept 8478 of the library's 9654 such steps split), or
        // a smooth ball riding an arc's circle (sim/arc_split.rs, every step while it rides).
        let whole_split = set.substepping == Substepping::Split
            || (set.substeps > 1 && (set.split_at_blows || contacts.arc_rider));
        let spin_split = set.substeps > 1 && contacts.spinning_ball && set.reads_contact_events;
        Work {
            steps,
            substeps: set.substeps,
            iterations: set.solver_iterations,
            // A step with a spinning ball in contact, or a smooth ball on an arc's circle, is
            // split as the run goes (sim/contact_points.rs, sim/arc_split.rs): priced so from
            // the start. A level whose joint impulses are reconstructed from one call
            // (`split_at_blows`, sim/joint_sums.rs) is priced split too.
            calls_per_step: if whole_split || spin_split {
                set.substeps
            } else {
                1
            },
            // A spinning ball splits a step only while its turn over a call would disturb its
            // contact: measured 2026-12-07 (`cargo bench --no-default-features --bench budget`,
            // the calls each report counts) on the library's levels priced split for a spinning
            // ball alone, 3% to 99% of their steps split, 40% to 50% in the middle.
            split_share: if whole_split || !spin_split {
                1.0
            } else {
                SPIN_SPLIT_SHARE
            },
            bodies: level.bodies.len(),
            joints: level.joints.len(),
            pairs: contacts.pairs + contacts.resting,
            resting_pairs: contacts.resting,
            pair_degrees: contacts.degrees,
            facets: level
                .bodies
                .iter()
                .filter_map(|b| b.shape.as_ref())
                .map(shapes::facets)
                .sum(),
            couplings: if set.effects.has(Effect::Joints) {
                level.couplings.len()
            } else {
                0
            },
            turning_couplings: if set.effects.has(Effect::Joints) {
                level
                    .couplings
                    .iter()
                    .filter(|c| c.terms.iter().any(|t| t.coordinate == Coordinate::Angle))
                    .count()
            } else {
                0
            },
            questions: level.questions.len(),
            // Every quantity of the periods family (questions/periods.rs) linearizes the
            // mechanism once.
            linearizations: level
                .questions
                .iter()
                .filter(|q| q.quantity.family() == QuantityFamily::Periods)
                .count(),
            reference_us: reference_us(level, steps * opts.dt.unwrap_or(level.world.dt)),
            mechanism: largest_mechanism(level),
            checks: level.checks.len(),
            virtual_work_joints: level
                .checks
                .iter()
                .filter(|c| c.kind == CheckKind::VirtualWork)
                .count()
                * level.joints.len(),
            history_bytes_per_step,
            f64: precision == crate::level::Precision::F64,
            dt: opts.dt.unwrap_or(level.world.dt),
            windows: Windows::of(level, opts.dt.unwrap_or(level.world.dt)),
            track_pairs: if set.impact_cuts {
                contacts.rider_pairs
            } else {
                0.0
            },
            polyline_facets: if set.impact_cuts {
                contacts.polyline_facets
            } else {
                0.0
            },
            other_tracks: if set.impact_cuts {
                contacts.other_tracks
            } else {
                0.0
            },
        }
    }

    /// The shape casts against curved tracks a call, priced: every call of a pair of a moving
    /// body and a curved track once calls are [`TRACK_CAST_CALL_S`] or shorter, none before.
    pub fn track_cast_us(&self) -> f64 {
        let call_s = self.dt / self.calls_per_step as f64;
        if call_s <= TRACK_CAST_CALL_S {
            self.track_pairs * TRACK_CAST_US
        } else {
            0.0
        }
    }

    /// rapier calls a step, priced: 1 + (calls_per_step - 1) x split_share.
    pub fn calls(&self) -> f64 {
        1.0 + (self.calls_per_step as f64 - 1.0) * self.split_share
    }

    /// The contact pairs as priced: those past [`PAIRS_IN_CACHE`] count [`PAIR_FAR_COST`] each.
    pub fn priced_pairs(&self) -> f64 {
        self.pairs.min(PAIRS_IN_CACHE) + (self.pairs - PAIRS_IN_CACHE).max(0.0) * PAIR_FAR_COST
    }

    /// The joints as priced: one each up to [`JOINTS_IN_LANES`], then the larger of that and
    /// [`JOINT_LANE_COST`] each, so that a joint more never lowers the price (255 joints priced
    /// 255 and 256 priced 90 would let a larger net pass where a smaller one is refused). The
    /// nets measured keep their ratios within 0.5x-2x: 414 joints priced 256 read 1.36x (0.77x
    /// at 0.35 each), 918 and 1734 are priced 0.35 each as before.
    pub fn priced_joints(&self) -> f64 {
        let n = self.joints as f64;
        n.min(JOINTS_IN_LANES as f64).max(n * JOINT_LANE_COST)
    }

    /// One linearization of the mechanism, us: [`LINEARIZE_US`], [`LINEARIZE_JOINT_US`] a
    /// joint, and [`LINEARIZE_SVD_US`] d^2 n^3 (see [`Work::mechanism`]).
    pub fn linearize_us(&self) -> f64 {
        let (n, d) = (self.mechanism.0 as f64, self.mechanism.1 as f64);
        LINEARIZE_US
            + self.joints as f64 * LINEARIZE_JOINT_US
            + LINEARIZE_SVD_US * d * d * n.powi(3)
    }

    /// One step, us.
    pub fn step_us(&self) -> f64 {
        let pairs = self.priced_pairs();
        let rows = self.priced_joints() + pairs;
        let engine = if self.f64 { F64_COST } else { 1.0 };
        let calls = self.calls();
        engine
            * (calls * (CALL_US + pairs * PAIR_CALL_US)
                + self.bodies as f64 * BODY_STEP_US
                + self.substeps as f64
                    * (SUBSTEP_US
                        + self.bodies as f64 * BODY_SUBSTEP_US
                        + rows * (ROW_SUBSTEP_US + self.iterations as f64 * ROW_ITERATION_US)))
            + calls
                * (self.couplings as f64 * COUPLING_CALL_US
                    + self.turning_couplings as f64 * COUPLING_ANGLE_CALL_US
                    + self.track_cast_us()
                    + self.polyline_facets * POLYLINE_FACET_CALL_US
                    + self.other_tracks * OTHER_TRACK_CALL_US)
            + self.windows.step_us()
            + self.questions as f64 * QUESTION_STEP_US
            + self.checks as f64 * CHECK_STEP_US
            + self.virtual_work_joints as f64 * VIRTUAL_WORK_JOINT_STEP_US
    }
}

impl Estimate {
    /// The estimate of running `level` with the overrides, as `mode` runs it, for `steps` steps
    /// (None: world.duration / dt).
    pub fn of(level: &Level, opts: &Options, mode: Mode, steps: Option<f64>) -> Estimate {
        Self::price(Work::of(level, opts, steps), mode)
    }

    /// The unit costs applied to `work`: the formula docs/cli.md states.
    pub fn price(work: Work, mode: Mode) -> Estimate {
        let linearize_us = work.linearize_us();
        let mut seconds = START_S
            + (RUN_US + work.linearizations as f64 * linearize_us + work.reference_us) * 1e-6
            + work.steps * work.step_us() * 1e-6
            + work.pair_degrees * PAIR_MADE_NS * 1e-9
            + work.facets * FACET_US * 1e-6;
        let mut megabytes = BASE_MB
            + (work.bodies as f64 * BODY_KB
                + work.joints as f64 * JOINT_KB
                + work.pairs * PAIR_KB
                + work.questions as f64 * QUESTION_KB)
                / 1024.0
            + work.steps * work.history_bytes_per_step / 1048576.0;
        if mode == Mode::Render {
            seconds += RENDER_S;
            megabytes += RENDER_MB;
        }
        Estimate {
            work,
            mode,
            seconds,
            megabytes,
        }
    }

    /// Whether the run fits the time and the memory budgets.
    pub fn fits(&self) -> bool {
        self.seconds <= TIME_BUDGET_S && self.megabytes <= MEMORY_BUDGET_MB
    }

    /// Bad input (exit 2), located at the level file, when the run would take more than
    /// [`TIME_BUDGET_S`] or [`MEMORY_BUDGET_MB`].
    pub fn within_budget(&self, file: &Path) -> Result<(), LevelError> {
        if self.fits() {
            return Ok(());
        }
        let w = &self.work;
        let mut what = format!(
            "{:.3e} steps x {} substeps x {} iterations, {} bodies, {} joints",
            w.steps, w.substeps, w.iterations, w.bodies, w.joints
        );
        if w.pairs > 0.0 {
            what += &format!(", {:.0} contact pairs", w.pairs);
        }
        if w.questions > 0 {
            what += &format!(", {} questions", w.questions);
        }
        let windowed = w.windows.motor + w.windows.contact + w.windows.joint;
        if w.windows.questions > 0 {
            what += &format!(
                " ({} windowed question{} reading {windowed:.0} snapshots a step)",
                w.windows.questions,
                if w.windows.questions == 1 { "" } else { "s" }
            );
        }
        if w.track_cast_us() > 0.0 {
            what += &format!(
                ", {:.0} bodies on curved tracks cast against their facets every call",
                w.track_pairs
            );
        }
        if w.history_bytes_per_step > 0.0 {
            what += &format!(", checks keeping {} bytes a step", w.history_bytes_per_step);
        }
        // Once-a-run costs that can be the bulk of a run of few steps: name them with their
        // price, so that the remedy (fewer period questions, a smaller mechanism) is seen.
        let linearize_s = w.linearizations as f64 * w.linearize_us() * 1e-6;
        if linearize_s > 0.5 * self.seconds {
            what += &format!(
                ", {} question{} linearizing a mechanism of {} degrees of freedom and {} coordinates ({}, most of the run)",
                w.linearizations,
                if w.linearizations == 1 { "" } else { "s" },
                w.mechanism.1,
                w.mechanism.0,
                seconds_text(linearize_s)
            );
        }
        if w.reference_us * 1e-6 > 0.5 * self.seconds {
            what += &format!(
                ", the reference trajectory integrated for the questions read on it ({}, most of the run)",
                seconds_text(w.reference_us * 1e-6)
            );
        }
        Err(LevelError::new(
            file,
            (0, 0),
            format!(
                "this run is estimated to take {} and {} ({what}), past the budget of {TIME_BUDGET_S:.0} s and {MEMORY_BUDGET_MB:.0} MB",
                seconds_text(self.seconds),
                megabytes_text(self.megabytes),
            ),
            "pass --allow-long to run it anyway, or use a larger --dt, fewer --substeps or --iterations, or a shorter world.duration (or --time)",
        ))
    }
}

fn seconds_text(s: f64) -> String {
    if s < 1e5 {
        format!("{s:.1} s")
    } else {
        format!("{s:.2e} s")
    }
}

fn megabytes_text(mb: f64) -> String {
    if mb < 1e5 {
        format!("{mb:.0} MB")
    } else {
        format!("{mb:.2e} MB")
    }
}

/// An axis-aligned box, (min, max).
type Aabb = crate::level::shape::Aabb;

/// The potential contact pairs at the start, counted by [`contact_pairs`].
#[derive(Debug, Default, Clone, Copy)]
struct Pairs {
    pairs: f64,
    /// Sum over the pairs of the pairs each pair's bodies are in.
    degrees: f64,
    /// Whether a ball that can spin is in one: a dynamic `Circle`, free to turn, with friction
    /// on or started turning (sim/contact_points.rs splits its steps while it turns).
    spinning_ball: bool,
    /// Whether a smooth dynamic `Circle` is in one with a fixed `Arc` (sim/arc_split.rs splits
    /// its steps while it rides the arc's circle).
    arc_rider: bool,
    /// Pairs of a dynamic ball and a fixed `Arc` (which cast against the arc at fine steps).
    rider_pairs: f64,
    /// Over the pairs of a moving body and a `Polyline`, the polyline's points.
    polyline_facets: f64,
    /// Over the moving bodies on a curved track at the start, the other curved tracks of the
    /// scene (a loop's ramp and its circle: the body meets the second on its way).
    other_tracks: f64,
    /// The pairs the loose bodies (dynamic, in no joint, in no pair at the start) make as they
    /// come to rest, where gravity pulls them onto something fixed ([`resting_pairs`]).
    resting: f64,
}

/// What a body may do in a pair that splits a step (see [`Pairs`]).
#[derive(Debug, Default, Clone, Copy)]
struct Splits {
    may_spin: bool,
    /// A dynamic `Circle` without friction.
    smooth_ball: bool,
    /// A fixed `Arc` without friction.
    smooth_arc: bool,
    /// A dynamic `Circle`.
    ball: bool,
    /// A fixed `Arc`.
    arc: bool,
    /// A body that is not fixed.
    moving: bool,
    /// A curved track: a shape with facets.
    curved: bool,
    /// A fixed `Polyline`'s points (0 for any other shape): a cast against it walks them.
    polyline_facets: f64,
}

impl Splits {
    fn of(b: &crate::level::BodyDef, friction: bool) -> Splits {
        let Some(shape) = b.shape.as_ref() else {
            return Splits::default();
        };
        let ball =
            b.kind == BodyKind::Dynamic && matches!(shape, crate::level::Shape::Circle { .. });
        let smooth = !friction || b.friction.unwrap_or(0.0) == 0.0;
        let arc = b.kind == BodyKind::Fixed && matches!(shape, crate::level::Shape::Arc { .. });
        Splits {
            may_spin: ball && !b.lock_rotation && (friction || b.omega != 0.0),
            smooth_ball: ball && smooth,
            smooth_arc: arc && smooth,
            ball,
            arc,
            moving: b.kind != BodyKind::Fixed,
            curved: shapes::facets(shape) > 0.0,
            polyline_facets: match shape {
                crate::level::Shape::Polyline { .. } => shapes::facets(shape),
                _ => 0.0,
            },
        }
    }

    /// Whether the pair of `self` and `other` rides the chord contact.
    fn arc_rider(self, other: Splits) -> bool {
        self.smooth_ball && other.smooth_arc || self.smooth_arc && other.smooth_ball
    }

    /// Whether the pair is a ball on an arc (riding or rolling).
    fn on_arc(self, other: Splits) -> bool {
        self.ball && other.arc || self.arc && other.ball
    }

    /// Whether the pair is a moving body and a curved track.
    fn on_track(self, other: Splits) -> bool {
        self.moving && other.curved || self.curved && other.moving
    }
}

/// The potential contact pairs at the start: pairs of bodies with shapes, not both fixed, whose
/// boxes overlap within 1 cm. A sweep along x; counting stops past [`PAIRS_COUNTED`].
/// `friction`: whether the run has friction, which turns a ball that rolls.
fn contact_pairs(level: &Level, friction: bool, gravity: bool) -> Pairs {
    const MARGIN: f64 = 0.01;
    let jointed: std::collections::HashSet<&str> = level
        .joints
        .iter()
        .flat_map(|j| [j.body1.as_str(), j.body2.as_str()])
        .collect();
    let mut boxes: Vec<(Aabb, bool, Splits, bool)> = level
        .bodies
        .iter()
        .filter_map(|b| {
            let shape = b.shape.as_ref()?;
            let bb = shapes::bounds(shape, b.position, b.angle);
            let finite = [bb.0 .0, bb.0 .1, bb.1 .0, bb.1 .1]
                .iter()
                .all(|v| v.is_finite());
            // Free: a dynamic body in no joint, which gravity brings to rest on something.
            let free = b.kind == BodyKind::Dynamic && !jointed.contains(b.name.as_str());
            finite.then_some((bb, b.kind == BodyKind::Fixed, Splits::of(b, friction), free))
        })
        .collect();
    boxes.sort_by(|a, b| a.0 .0 .0.total_cmp(&b.0 .0 .0));
    let mut degree = vec![0usize; boxes.len()];
    let mut pairs = 0.0;
    let mut spinning_ball = false;
    let mut arc_rider = false;
    let mut rider_pairs = 0.0;
    let mut polyline_facets = 0.0;
    let mut on_tracks = vec![0usize; boxes.len()];
    'sweep: for i in 0..boxes.len() {
        let (a, fixed_a, spin_a, _) = boxes[i];
        for j in i + 1..boxes.len() {
            let (b, fixed_b, spin_b, _) = boxes[j];
            if b.0 .0 > a.1 .0 + MARGIN {
                break;
            }
            if fixed_a && fixed_b || b.0 .1 > a.1 .1 + MARGIN || a.0 .1 > b.1 .1 + MARGIN {
                continue;
            }
            degree[i] += 1;
            degree[j] += 1;
            pairs += 1.0;
            spinning_ball |= spin_a.may_spin || spin_b.may_spin;
            arc_rider |= spin_a.arc_rider(spin_b);
            if spin_a.on_track(spin_b) {
                rider_pairs += f64::from(u8::from(spin_a.on_arc(spin_b)));
                polyline_facets += spin_a.polyline_facets + spin_b.polyline_facets;
                on_tracks[if spin_a.moving { i } else { j }] += 1;
            }
            if pairs >= PAIRS_COUNTED {
                break 'sweep;
            }
        }
    }
    let fixed = boxes.iter().any(|b| b.1);
    let tracks = boxes.iter().filter(|b| b.1 && b.2.curved).count();
    // A loose ball that can spin rolls as it comes to rest: its steps are split as for a ball in
    // a pair at the start.
    let loose_spinner = boxes
        .iter()
        .zip(&degree)
        .any(|(b, &d)| b.3 && d == 0 && b.2.may_spin);
    let other_tracks = on_tracks
        .iter()
        .filter(|&&n| n > 0)
        .map(|&n| tracks.saturating_sub(n) as f64)
        .sum();
    let loose = boxes
        .iter()
        .zip(&degree)
        .filter(|(b, &d)| b.3 && d == 0)
        .count();
    // Sum over the pairs of their bodies' pairs: sum over the bodies of d^2.
    Pairs {
        pairs,
        resting: if gravity && fixed {
            resting_pairs(loose as f64)
        } else {
            0.0
        },
        degrees: degree.iter().map(|&d| (d as f64).powi(2)).sum(),
        spinning_ball: spinning_ball || (gravity && fixed && loose_spinner),
        arc_rider,
        rider_pairs,
        polyline_facets,
        other_tracks,
    }
}

/// The contact pairs `n` loose bodies hold once gravity has brought them to rest in a heap (a
/// heap of grains poured into a bin has none at the start: issue 45's sand pile, 0 pairs at its
/// start and 28,000 contact manifolds settled), counted as n equal discs packed in a triangle of
/// side k, n = k (k + 1) / 2: 3 k (k - 1) / 2 pairs between discs and k on the floor, about
/// 3 n - 2.83 sqrt(n); at least n (each rests on something).
fn resting_pairs(n: f64) -> f64 {
    (3.0 * n - 2.83 * n.sqrt()).max(n)
}
