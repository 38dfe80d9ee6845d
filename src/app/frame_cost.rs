//! What a frame costs on a computer without a GPU, and the two choices that halve it.
//!
//! Measured under Xvfb with Mesa's llvmpipe on this project's 2-core machine (1440x900, the
//! large-amplitude physical pendulum with every overlay on; docs/sandbox.md, "Frame rate"):
//! - **Samples per pixel.** llvmpipe shades every sample on the CPU: 4x MSAA drew 12 fps, none
//!   24 fps. On a CPU adapter the scene is drawn without MSAA (egui antialiases its own edges).
//! - **Bevy's multi-threaded executor.** It hands each system to a task pool thread and parks
//!   and wakes threads around it; with two cores shared with llvmpipe's two rasterizer threads,
//!   58% of the process's samples were in the kernel switching threads. The sandbox's systems
//!   are light and mostly in sequence (the physics is one system), so the native window runs
//!   every schedule on one thread: 24 fps became 33 fps, and the four-bar, whose physics steps
//!   at 10 kHz, went from 3 fps (falling behind real time) to 28 fps.
//!
//! - **Pipelined rendering.** Bevy renders frame n while it updates frame n + 1, so a key shows
//!   a frame late. Without the pipeline a key read in an update is drawn by that same update:
//!   input shows on the next frame. It cost nothing on the pendulum (34 to 35 fps either way)
//!   and 5% where the physics is heavy (four-bar 27 against 28.5 fps, pyramid 16 to 19 against
//!   18), which the window pays for its responsiveness.
//!
//! `RIGIDLAB_MSAA=off|4`, `RIGIDLAB_EXECUTOR=multi` and `RIGIDLAB_PIPELINE=1` bring back each
//! choice to measure it.

use bevy::app::PluginGroupBuilder;
use bevy::ecs::schedule::{Schedules, SingleThreadedExecutor};
use bevy::prelude::*;
use bevy::render::renderer::RenderAdapterInfo;

/// How many samples per pixel the scene is drawn with: none on a CPU renderer (llvmpipe
/// natively, and a web page, where WebGL2 is SwiftShader on a machine without a GPU), 4x on a
/// GPU.
pub fn scene_samples(adapter: Option<&RenderAdapterInfo>) -> Msaa {
    match std::env::var("RIGIDLAB_MSAA").as_deref() {
        Ok("off" | "1") => return Msaa::Off,
        Ok("4") => return Msaa::Sample4,
        _ => {}
    }
    // wgpu's DeviceType is not re-exported by bevy_render: its name is compared instead.
    let on_cpu = adapter.is_some_and(|a| format!("{:?}", a.device_type) == "Cpu");
    if cfg!(target_arch = "wasm32") || on_cpu {
        Msaa::Off
    } else {
        Msaa::Sample4
    }
}

/// Runs every schedule of the app and of its render world on one thread (see the module's
/// note), unless `RIGIDLAB_EXECUTOR=multi`. Call once all plugins are added: schedules created
/// later keep Bevy's default executor.
pub fn choose_executor(app: &mut App) {
    if std::env::var("RIGIDLAB_EXECUTOR").as_deref() == Ok("multi") {
        return;
    }
    single_threaded(app.world_mut());
    if let Some(render) = app.get_sub_app_mut(bevy::render::RenderApp) {
        single_threaded(render.world_mut());
    }
}

fn single_threaded(world: &mut World) {
    if let Some(mut schedules) = world.get_resource_mut::<Schedules>() {
        for (_, schedule) in schedules.iter_mut() {
            schedule.set_executor(SingleThreadedExecutor::new());
        }
    }
}

/// Bevy's plugins without pipelined rendering (see the module's note), unless
/// `RIGIDLAB_PIPELINE=1`.
pub fn without_render_pipeline(plugins: PluginGroupBuilder) -> PluginGroupBuilder {
    // A web page has no render thread to pipeline (bevy_render has no such plugin there).
    #[cfg(not(target_arch = "wasm32"))]
    if std::env::var_os("RIGIDLAB_PIPELINE").is_none() {
        return plugins.disable::<bevy::render::pipelined_rendering::PipelinedRenderingPlugin>();
    }
    plugins
}
