//! `rigidlab render LEVEL --time T --out FILE.png`: the scene and its overlays at time T, drawn
//! by the real renderer into an image (no window, no X server; Mesa's lavapipe where there is no
//! GPU). The physics runs headless to T first, step by step as in `rigidlab check`.

use super::overlays::Overlays;
use super::physics::LiveChecks;
use super::playback::Playback;
use super::run::Run;
use super::scene::ScenePlugins;
use super::view::{palette, View, WorldCamera};
use crate::level::Scene;
use crate::sim::Options;
use bevy::app::SubApps;
use bevy::asset::RenderAssetUsages;
use bevy::camera::visibility::RenderLayers;
use bevy::camera::{CameraOutputMode, RenderTarget};
use bevy::prelude::*;
use bevy::render::render_resource::{
    BlendState, Extent3d, PollType, TextureDimension, TextureFormat, TextureUsages,
};
use bevy::render::renderer::RenderDevice;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::render::RenderPlugin;
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use bevy_egui::{EguiGlobalSettings, EguiPlugin, PrimaryEguiContext};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// What to draw.
#[derive(Debug, Clone)]
pub struct RenderOptions {
    pub width: u32,
    pub height: u32,
    pub overlays: Overlays,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 1024,
            height: 640,
            overlays: Overlays {
                velocity: true,
                free_body: true,
                trails: true,
                labels: true,
                names: false,
                ..Overlays::default()
            },
        }
    }
}

impl RenderOptions {
    /// Overlays from letters as the sandbox keys name them: v a c f k h t l n
    /// (velocity, acceleration, instant center, free body, kinetic, momentum, trails, labels,
    /// names).
    pub fn overlays_from_letters(letters: &str) -> Result<Overlays, String> {
        let mut o = Overlays {
            velocity: false,
            acceleration: false,
            instant_center: false,
            free_body: false,
            kinetic: false,
            momentum: false,
            trails: false,
            labels: false,
            names: false,
            ..Overlays::default()
        };
        for c in letters.chars().filter(|c| !c.is_whitespace() && *c != ',') {
            match c.to_ascii_lowercase() {
                'v' => o.velocity = true,
                'a' => o.acceleration = true,
                'c' => o.instant_center = true,
                'f' => o.free_body = true,
                'k' => o.kinetic = true,
                'h' => o.momentum = true,
                't' => o.trails = true,
                'l' => o.labels = true,
                'n' => o.names = true,
                other => {
                    return Err(format!(
                        "unknown overlay `{other}`: use letters from vacfkhtln \
                         (velocity, acceleration, instant center, free body, kinetic, momentum, trails, labels, names)"
                    ))
                }
            }
        }
        Ok(o)
    }
}

/// Where the Vulkan loader and drivers are looked for (Bevy 0.19 renders through Vulkan only).
pub fn vulkan_check() -> Result<(), String> {
    let loader_dirs = [
        "/usr/lib/x86_64-linux-gnu",
        "/usr/lib/aarch64-linux-gnu",
        "/usr/lib64",
        "/usr/lib",
        "/lib/x86_64-linux-gnu",
        "/usr/local/lib",
    ];
    let mut dirs: Vec<PathBuf> = loader_dirs.iter().map(PathBuf::from).collect();
    if let Some(extra) = std::env::var_os("LD_LIBRARY_PATH") {
        dirs.extend(std::env::split_paths(&extra));
    }
    let loader = dirs.iter().any(|d| d.join("libvulkan.so.1").exists());

    let mut icds: Vec<PathBuf> = Vec::new();
    for var in ["VK_ICD_FILENAMES", "VK_DRIVER_FILES"] {
        if let Some(v) = std::env::var_os(var) {
            icds.extend(std::env::split_paths(&v).filter(|p| p.exists()));
        }
    }
    let mut icd_dirs: Vec<PathBuf> = [
        "/etc/vulkan/icd.d",
        "/usr/share/vulkan/icd.d",
        "/usr/local/share/vulkan/icd.d",
    ]
    .iter()
    .map(PathBuf::from)
    .collect();
    for (var, default) in [("XDG_DATA_DIRS", ""), ("XDG_CONFIG_DIRS", "")] {
        let v = std::env::var(var).unwrap_or_else(|_| default.to_string());
        icd_dirs.extend(
            v.split(':')
                .filter(|s| !s.is_empty())
                .map(|d| Path::new(d).join("vulkan/icd.d")),
        );
    }
    for d in icd_dirs {
        if let Ok(rd) = std::fs::read_dir(&d) {
            icds.extend(
                rd.filter_map(|e| e.ok())
                    .map(|e| e.path())
                    .filter(|p| p.extension().is_some_and(|x| x == "json")),
            );
        }
    }
    let help = "rendering needs a Vulkan driver. Without a GPU, install Mesa's software one:\n    \
                sudo apt-get install mesa-vulkan-drivers libvulkan1\n\
                (the headless checks need none: rigidlab check levels)";
    match (loader, icds.is_empty()) {
        (true, false) => Ok(()),
        (false, _) => Err(format!("rigidlab render: no Vulkan loader (libvulkan.so.1) found; {help}")),
        (true, true) => Err(format!("rigidlab render: no Vulkan driver (ICD file in /usr/share/vulkan/icd.d or /etc/vulkan/icd.d) found; {help}")),
    }
}

/// The Vulkan loader probes for a Wayland display and prints "error: XDG_RUNTIME_DIR is invalid"
/// when the variable is unset (containers, CI); a successful render should not print errors, so
/// give it a private empty runtime dir. Called before Bevy starts any thread.
fn quiet_wayland_probe() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        let dir = std::env::temp_dir().join("rigidlab-xdg-runtime");
        if std::fs::create_dir_all(&dir).is_ok() {
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                let _ = std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700));
            }
            std::env::set_var("XDG_RUNTIME_DIR", &dir);
        }
    }
}

/// A rendered frame, RGBA8 (sRGB).
pub struct Frame {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
}

/// Runs the scene to `time` and renders it with `opts`; writes `out` (PNG) when given.
pub fn render_frame(
    scene: &Scene,
    time: f64,
    out: Option<&Path>,
    opts: &RenderOptions,
) -> Result<Frame, String> {
    vulkan_check()?;
    quiet_wayland_probe();
    // Runs past the level's end when asked a later time: `advance` steps whatever the playback.
    let mut phys = Run::new(scene.clone(), Options::default());
    let mut live = LiveChecks::new(&phys);
    let steps = (time / phys.sim.dt()).round() as u64;
    for _ in 0..steps {
        if !phys.advance() {
            return Err(format!(
                "{}: {}",
                scene.file.display(),
                phys.error.clone().unwrap_or_default()
            ));
        }
        live.observe(&phys);
    }

    // Bevy reports a missing or broken GPU by panicking: turn that into an error.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|info| {
        eprintln!("rigidlab render: the renderer failed: {info}");
    }));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        run_renderer(phys, live, out, opts)
    }));
    std::panic::set_hook(hook);
    match result {
        Ok(r) => r,
        Err(_) => Err(
            "rigidlab render: the renderer could not start (see the message above); \
                       check the Vulkan driver with `vulkaninfo --summary`"
                .into(),
        ),
    }
}

type Captured = Arc<Mutex<Option<Result<Frame, String>>>>;

fn run_renderer(
    phys: Run,
    live: LiveChecks,
    out: Option<&Path>,
    opts: &RenderOptions,
) -> Result<Frame, String> {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            .set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                ..default()
            })
            .set(bevy::log::LogPlugin {
                level: bevy::log::Level::ERROR,
                ..default()
            })
            .disable::<WinitPlugin>(),
    );
    app.add_plugins(EguiPlugin::default());
    app.world_mut()
        .resource_mut::<EguiGlobalSettings>()
        .auto_create_primary_context = false;
    app.insert_resource(ClearColor(palette::BACKGROUND));
    app.insert_resource(Time::<Fixed>::from_seconds(phys.sim.dt()));
    app.insert_non_send(live);
    app.insert_resource(phys);
    app.insert_resource(Playback::new(true));
    app.insert_resource(opts.overlays.clone());
    app.insert_resource(View {
        viewport: Rect::new(0.0, 0.0, opts.width as f32, opts.height as f32),
        ..default()
    });
    app.add_plugins(ScenePlugins { legend: true });
    app.finish();
    app.cleanup();
    let mut apps: SubApps = std::mem::take(app.sub_apps_mut());

    let mut target = Image::new_uninit(
        Extent3d {
            width: opts.width,
            height: opts.height,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::RENDER_WORLD,
    );
    target.texture_descriptor.usage |= TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC;
    let world = apps.main.world_mut();
    let handle = world.resource_mut::<Assets<Image>>().add(target);
    world.spawn((
        Camera2d,
        WorldCamera,
        RenderTarget::Image(handle.clone().into()),
        Msaa::Sample4,
    ));
    // Labels and legend: egui on a second camera drawn over the scene into the same image.
    world.spawn((
        PrimaryEguiContext,
        Camera2d,
        RenderLayers::none(),
        RenderTarget::Image(handle.clone().into()),
        Camera {
            order: 1,
            output_mode: CameraOutputMode::Write {
                blend_state: Some(BlendState::ALPHA_BLENDING),
                clear_color: ClearColorConfig::None,
            },
            clear_color: ClearColorConfig::Custom(Color::NONE),
            ..default()
        },
    ));

    let update = |apps: &mut SubApps| -> Result<(), String> {
        apps.update();
        apps.main
            .world()
            .resource::<RenderDevice>()
            .wgpu_device()
            .poll(PollType::Wait {
                submission_index: None,
                timeout: None,
            })
            .map(|_| ())
            .map_err(|e| format!("rigidlab render: the GPU did not finish the frame: {e}"))
    };
    // A few frames: meshes, pipelines, egui fonts and the camera fit settle.
    for _ in 0..4 {
        update(&mut apps)?;
    }
    let captured: Captured = Arc::new(Mutex::new(None));
    let slot = captured.clone();
    let path = out.map(Path::to_path_buf);
    apps.main
        .world_mut()
        .spawn(Screenshot::image(handle))
        .observe(move |shot: On<ScreenshotCaptured>| {
            let result = frame_of(&shot.image, path.as_deref());
            *slot.lock().unwrap() = Some(result);
        });
    for _ in 0..30 {
        update(&mut apps)?;
        if let Some(r) = captured.lock().unwrap().take() {
            return r;
        }
    }
    Err("rigidlab render: the screenshot never arrived from the renderer".into())
}

fn frame_of(image: &Image, out: Option<&Path>) -> Result<Frame, String> {
    let dynamic = image
        .clone()
        .try_into_dynamic()
        .map_err(|e| format!("rigidlab render: cannot read the rendered image: {e}"))?;
    let rgba = dynamic.to_rgba8();
    if let Some(path) = out {
        // Encoded in memory, then written whole beside the destination and renamed over it: a
        // failed render leaves an earlier image as it was.
        let rgb = dynamic.to_rgb8();
        let write = |e: String| format!("rigidlab render: cannot write {}: {e}", path.display());
        let bytes = crate::files::png_bytes(rgb.width(), rgb.height(), false, rgb.as_raw())
            .map_err(write)?;
        crate::files::write_over_own(path, &bytes, crate::files::Mark::Png)
            .map_err(|e| write(e.to_string()))?;
    }
    Ok(Frame {
        width: rgba.width(),
        height: rgba.height(),
        rgba: rgba.into_raw(),
    })
}
