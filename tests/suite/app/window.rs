//! The sandbox window itself, as `rigidlab play` opens it: under a display (CI runs the tests
//! under Xvfb with Mesa's software Vulkan) it draws 150 frames of a library level without one
//! rendering error and closes cleanly. A window whose cameras disagreed on multisampling drew
//! nothing but validation errors while every other test passed: this is the test that sees it.

use std::process::Command;

#[test]
fn the_window_draws_frames_without_rendering_errors() {
    if let Err(why) = rigidlab::app::render::vulkan_check() {
        assert!(
            std::env::var_os("RIGIDLAB_REQUIRE_RENDER").is_none(),
            "the window test cannot run: {why}"
        );
        println!("skipped: {why}");
        return;
    }
    if std::env::var_os("DISPLAY").is_none() {
        assert!(
            std::env::var_os("RIGIDLAB_REQUIRE_RENDER").is_none(),
            "the window test needs a display (run the tests under xvfb-run)"
        );
        println!("skipped: no DISPLAY");
        return;
    }
    let out = Command::new(env!("CARGO_BIN_EXE_rigidlab"))
        .args(["play", "levels/kinetics/physical_pendulum.ron"])
        .env("RIGIDLAB_CONTINUOUS", "1")
        .env("RIGIDLAB_FPS_LOG", "1")
        .env("RIGIDLAB_EXIT_AFTER_FRAMES", "150")
        // Not the user's own preferences: the test writes what the window remembers elsewhere.
        .env(
            "RIGIDLAB_PREFS",
            std::env::temp_dir().join(format!("rigidlab-window-prefs-{}.ron", std::process::id())),
        )
        .env("NO_COLOR", "1")
        .output()
        .expect("rigidlab play runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    let errors: Vec<&str> = stderr
        .lines()
        .filter(|l| l.contains("ERROR") || l.contains("panicked"))
        .collect();
    assert!(
        out.status.success(),
        "rigidlab play exited with {}: {}",
        out.status,
        errors.join("\n")
    );
    assert!(
        errors.is_empty(),
        "rendering errors:\n{}",
        errors.join("\n")
    );
    let rate = stderr
        .lines()
        .rfind(|l| l.contains("frame rate:"))
        .expect("the window reported its frame rate after 120 frames");
    println!("{}", rate.trim());
}
