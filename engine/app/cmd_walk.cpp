// forest walk: the scene in a window. The renderer draws into its own image exactly as for
// `forest render`; the present step (engine/present/present.h) copies it to the swapchain with
// the HUD on top. Keys switch prune modes and views; WASD + mouse fly the camera.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/tools/bake/species_cache.h"
#include "engine/app/app_common.h"
#include "engine/app/commands.h"
#include "engine/present/hud.h"
#include "engine/present/image_io.h"
#include "engine/present/present.h"
#include "engine/render/renderer.h"
#include "engine/scene/fly_camera.h"
#include "engine/scene/scene.h"
#include "engine/scene/camera_path.h"
#include "engine/vk/swapchain.h"
#include "generators/core/input_error.h"

namespace forest::app {

namespace {

constexpr double kScriptedStep = 1.0 / 30.0;  // seconds per frame with --frames: same run, same frames
constexpr uint32_t kMaxOverlayBytes = 2048 * 512 * 4;

// Camera path playback ([P]): the scene's first [[path]], looping over its duration.
struct CameraPlayback {
  std::function<CameraDesc(double seconds)> at;  // empty: the scene has no camera path
};
CameraPlayback scene_camera_playback(const Scene& scene) {
  if (scene.desc.paths.empty()) return {};
  const CameraPath* path = &scene.desc.paths.front();
  const CameraDesc base = scene.desc.camera;
  const double duration = std::max(double(path_duration(*path)), 1e-3);
  return {[path, base, duration](double seconds) {
    return camera_at(*path, path->keys.front().time + float(std::fmod(seconds, duration)), base);
  }};
}

// What the GLFW callbacks change; read once per frame by the loop.
struct WalkState {
  FrameSettings settings;
  bool hud = true;
  bool wireframe_available = false;
  bool playback_available = false;
  bool playing = false;
  bool screenshot = false;
  bool freeze_lod = false;  // K: keep choosing LODs and λ from where K was pressed
  bool framebuffer_changed = false;
  double wheel = 0.0;
  std::string message;  // shown on the HUD for a few seconds
  double message_time = -1.0;
  double now = 0.0;
};

void say(WalkState& s, std::string text) {
  s.message = std::move(text);
  s.message_time = s.now;
}

void on_key(GLFWwindow* window, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  auto& s = *static_cast<WalkState*>(glfwGetWindowUserPointer(window));
  switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); break;
    case GLFW_KEY_1: s.settings.prune_mode = PruneMode::full; break;
    case GLFW_KEY_2: s.settings.prune_mode = PruneMode::cook; break;
    case GLFW_KEY_3: s.settings.prune_mode = PruneMode::opt; break;
    case GLFW_KEY_4: s.settings.prune_mode = PruneMode::target; break;
    case GLFW_KEY_O: s.settings.occlusion = !s.settings.occlusion; break;
    case GLFW_KEY_J: s.settings.shadows = !s.settings.shadows; break;
    case GLFW_KEY_I:
      s.settings.impostors = s.settings.impostors == ImpostorMode::off ? ImpostorMode::switched : ImpostorMode::off;
      break;
    case GLFW_KEY_L: s.settings.lambda_view = !s.settings.lambda_view; break;
    case GLFW_KEY_Y:
      s.settings.pyramid_overlay = !s.settings.pyramid_overlay;
      if (s.settings.pyramid_overlay && !s.settings.occlusion) say(s, "the depth pyramid overlay shows with occlusion on ([O])");
      break;
    case GLFW_KEY_F:
      if (s.wireframe_available) s.settings.wireframe = !s.settings.wireframe;
      else say(s, "wireframe needs the fillModeNonSolid device feature");
      break;
    case GLFW_KEY_H: s.hud = !s.hud; break;
    case GLFW_KEY_K:
      s.freeze_lod = !s.freeze_lod;
      if (!s.freeze_lod) s.settings.lod_camera.reset();
      break;
    case GLFW_KEY_P:
      if (s.playback_available) s.playing = !s.playing;
      else say(s, "this scene has no camera path");
      break;
    case GLFW_KEY_C:
    case GLFW_KEY_F12: s.screenshot = true; break;
    default: break;
  }
}

void on_scroll(GLFWwindow* window, double, double y) {
  static_cast<WalkState*>(glfwGetWindowUserPointer(window))->wheel += y;
}

void on_framebuffer_size(GLFWwindow* window, int, int) {
  static_cast<WalkState*>(glfwGetWindowUserPointer(window))->framebuffer_changed = true;
}

std::string glfw_error;
void on_glfw_error(int, const char* text) { glfw_error = text ? text : "unknown GLFW error"; }

VkExtent2D framebuffer_extent(GLFWwindow* window) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window, &w, &h);
  return {uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0))};
}


std::string format(const char* fmt, auto... values) {
  char line[256];
  std::snprintf(line, sizeof(line), fmt, values...);
  return line;
}

std::vector<std::string> hud_lines(const WalkState& s, const FrameStats& st, const FlyCamera& cam, double fps,
                                   double cpu_ms, std::string device) {
  device = device.substr(0, device.find(" ("));  // "llvmpipe (LLVM 15.0.6, 256 bits)" -> "llvmpipe"
  const FrameSettings& f = s.settings;
  std::vector<std::string> lines = {
      format("%.3g fps  %.1f ms  %s", fps, cpu_ms, device.c_str()),
      format("GPU ms: cull %.2f draw %.2f frame %.2f", st.cull_ms, st.draw_ms, st.frame_ms),
      format("trees %u/%u  branch tris %u", st.branch_draws, st.instances, st.branch_triangles),
      format("leaves %u  mean lambda %.3f", st.leaves_drawn, st.mean_lambda),
      format("[1-4] prune %s  [L] %s  [F] wire %s", prune_mode_name(f.prune_mode), f.lambda_view ? "lambda" : "shaded",
             f.wireframe ? "on" : "off"),
      format("[O] occlusion %s (%u culled)  [P] path %s", f.occlusion ? "on" : "off", st.occluded_instances,
             !s.playback_available ? "none" : s.playing ? "playing" : "stopped"),
      format("%.0f %.0f %.0f  %.1f m/s  [C] shot  [J] shadows %s", cam.position.x, cam.position.y, cam.position.z,
             cam.speed, f.shadows ? "on" : "off"),
  };
  if (f.lod_camera) lines.push_back("[K] LOD frozen");
  if (!s.message.empty() && s.now - s.message_time < 4.0) lines.push_back(s.message);
  return lines;
}

FlyInput keyboard_and_mouse(GLFWwindow* window, glm::dvec2& last_cursor) {
  FlyInput in;
  auto held = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS ? 1.0f : 0.0f; };
  in.forward = held(GLFW_KEY_W) - held(GLFW_KEY_S);
  in.right = held(GLFW_KEY_D) - held(GLFW_KEY_A);
  in.up = held(GLFW_KEY_E) + held(GLFW_KEY_SPACE) - held(GLFW_KEY_Q);
  in.fast = held(GLFW_KEY_LEFT_SHIFT) > 0.0f || held(GLFW_KEY_RIGHT_SHIFT) > 0.0f;
  glm::dvec2 cursor;
  glfwGetCursorPos(window, &cursor.x, &cursor.y);
  // Look while a mouse button is held: the cursor stays free for the window otherwise.
  if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS ||
      glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
    in.look_x = float(cursor.x - last_cursor.x);
    in.look_y = float(cursor.y - last_cursor.y);
  }
  last_cursor = cursor;
  return in;
}

// Waits (bounded) until the window's framebuffer has the size asked for: X servers
// answer a resize asynchronously.
void wait_for_framebuffer(GLFWwindow* window, VkExtent2D wanted) {
  for (int i = 0; i < 100; ++i) {
    VkExtent2D e = framebuffer_extent(window);
    if (e.width == wanted.width && e.height == wanted.height) return;
    glfwWaitEventsTimeout(0.02);
  }
}

// Presenter and swapchain are released before the renderer and the context, also on errors.
struct PresentTargets {
  vk::Context& ctx;
  vk::Swapchain swapchain;
  Presenter presenter;
  ~PresentTargets() {
    destroy_presenter(ctx, presenter);
    vk::destroy_swapchain(ctx, swapchain);
  }
};

struct Window {
  GLFWwindow* window = nullptr;
  ~Window() {
    if (window) glfwDestroyWindow(window);
    glfwTerminate();
  }
};


using clock = std::chrono::steady_clock;

// Frame rate for the HUD, over half-second windows: readable, still current.
struct FpsMeter {
  clock::time_point start = clock::now();
  uint32_t frames = 0;
  double fps = 0.0, cpu_ms = 0.0;
};

void count_frame(FpsMeter& m) {
  ++m.frames;
  double window_s = std::chrono::duration<double>(clock::now() - m.start).count();
  if (window_s >= 0.5) {
    m.fps = m.frames / window_s;
    m.cpu_ms = 1000.0 * window_s / m.frames;
    m.start = clock::now();
    m.frames = 0;
  }
}

// Everything one walk draws with, and what it keeps from frame to frame.
struct Walk {
  const WalkArgs& args;
  const SceneDesc& desc;
  const Scene& scene;
  GLFWwindow* window;
  vk::Context& ctx;
  Renderer& renderer;
  vk::Swapchain& swapchain;
  Presenter& presenter;
  WalkState& state;
  CameraPlayback playback;
  bool hud_bgra = false;
  bool have_swapchain = false;
  FlyCamera camera;
  glm::dvec2 cursor{0.0};
  double play_time = 0.0;
  FrameStats stats;  // of the last frame the GPU finished
  uint32_t frame = 0, shots = 0;
  clock::time_point start{}, last{};
  FpsMeter fps;
};

// Opens the window at the scene's render size (GLFW is terminated by ~Window, also on errors).
void open_window(Window& win, const SceneDesc& desc, const std::string& scene_file) {
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit())
    throw vk::VkFailure("cannot open a window: " + glfw_error + " (no display? run under xvfb-run)");
  if (!glfwVulkanSupported()) throw vk::VkFailure("cannot open a window: GLFW finds no Vulkan loader");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  std::string title = "forest walk - " + scene_file;
  win.window = glfwCreateWindow(int(desc.width), int(desc.height), title.c_str(), nullptr, nullptr);
  if (!win.window) throw vk::VkFailure("cannot open a window: " + glfw_error);
}

// A context that can present to `window`: GLFW's instance extensions and the window's surface.
vk::ContextOptions window_context_options(const WalkArgs& args, GLFWwindow* window) {
  vk::ContextOptions options = context_options(args.device, args.validate);
  uint32_t glfw_extension_count = 0;
  const char** glfw_extensions = glfwGetRequiredInstanceExtensions(&glfw_extension_count);
  options.instance_extensions.assign(glfw_extensions, glfw_extensions + glfw_extension_count);
  options.create_surface = [window](VkInstance instance) {
    VkSurfaceKHR surface;
    VK_CHECK(glfwCreateWindowSurface(instance, window, nullptr, &surface));
    return surface;
  };
  return options;
}

void listen_to_window(GLFWwindow* window, WalkState& state) {
  glfwSetWindowUserPointer(window, &state);
  glfwSetKeyCallback(window, on_key);
  glfwSetScrollCallback(window, on_scroll);
  glfwSetFramebufferSizeCallback(window, on_framebuffer_size);
}

// After a (re)created swapchain: blit where the formats allow it, else the copy pass
// (--present forces either); the HUD needs a swapchain of 8-bit RGBA or BGRA.
void choose_present_path(Walk& w) {
  std::string why;
  bool blit = can_present(w.ctx, w.renderer.color_image().format, w.swapchain.format, &why);
  if (w.args.present == "blit" && !blit) throw vk::VkFailure("--present blit: " + why);
  bool pass = w.args.present == "pass" || !blit;
  if (pass && !w.presenter.copy_pass && w.args.present != "pass")
    std::fprintf(stderr, "forest: %s; using the copy pass\n", why.c_str());
  w.presenter.copy_pass = pass;
  if (!overlay_byte_order(w.swapchain.format, &w.hud_bgra)) w.state.hud = false;
}

// False when there is nothing to present to this time round: a minimized window (waits
// for events), or a swapchain that could not be created for the framebuffer yet.
bool ready_to_present(Walk& w) {
  VkExtent2D fb = framebuffer_extent(w.window);
  if (fb.width == 0 || fb.height == 0) {
    glfwWaitEvents();
    return false;
  }
  if (w.have_swapchain && !w.state.framebuffer_changed) return true;
  w.state.framebuffer_changed = false;
  w.have_swapchain = vk::create_swapchain(w.ctx, w.swapchain, fb);
  if (!w.have_swapchain) return false;
  choose_present_path(w);
  return true;
}

// Moves the camera by this frame's time step: along the camera path while it plays, else
// by keyboard and mouse (or the scripted --fly), kept above the terrain.
void move_camera(Walk& w) {
  auto now = clock::now();
  double dt = w.args.frames ? kScriptedStep : std::chrono::duration<double>(now - w.last).count();
  w.last = now;
  w.state.now = std::chrono::duration<double>(now - w.start).count();
  FlyInput input = keyboard_and_mouse(w.window, w.cursor);
  input.speed_steps = float(w.state.wheel);
  w.state.wheel = 0.0;
  if (w.args.fly) {  // scripted: forward while turning slowly right
    input.forward = 1.0f;
    input.look_x = 4.0f;
  }
  if (w.state.playing) {
    w.play_time += dt;
    FlyCamera from_path = fly_camera_from(w.playback.at(w.play_time));
    from_path.speed = w.camera.speed;
    from_path.moved = true;
    w.camera = from_path;
  } else {
    fly_update(w.camera, input, float(dt), &w.scene.terrain);
  }
}

OverlayImage hud_overlay(const Walk& w) {
  uint32_t scale = w.swapchain.extent.height >= 1000 ? 2 : 1;
  OverlayImage overlay = draw_text_panel(
      hud_lines(w.state, w.stats, w.camera, w.fps.fps, w.fps.cpu_ms, w.ctx.properties.deviceName), scale, w.hud_bgra);
  if (overlay.bytes.size() > kMaxOverlayBytes) overlay = {};
  return overlay;
}

// A scripted run's last frame is kept for after the validation verdict; a [C] shot is
// written at once, to --screenshot or to forest_walk_NNN.png.
void keep_screenshot(Walk& w, FrameImage& shot, FrameImage& final_shot) {
  if (w.args.frames) {
    final_shot = std::move(shot);  // written after the validation check in run_walk
    return;
  }
  std::filesystem::path p = w.args.screenshot.empty()
                                ? std::filesystem::path(format("forest_walk_%03u.png", w.shots))
                                : std::filesystem::path(w.args.screenshot);
  write_image(shot, p);
  ++w.shots;
  say(w.state, "wrote " + p.string());
}

// Draws and presents one frame (with the HUD and any screenshot asked for); true when it
// was the last frame of a scripted run.
bool draw_frame(Walk& w, FrameImage& final_shot) {
  if (w.state.freeze_lod && !w.state.settings.lod_camera) w.state.settings.lod_camera = w.camera.position;
  // Two frames in flight: the GPU draws this frame while the CPU prepares the next; the
  // HUD shows the statistics of the frame two back, whose queries are done by now.
  if (std::optional<FrameStats> done = w.renderer.render_async(fly_camera_desc(w.camera), w.state.settings))
    w.stats = *done;
  OverlayImage overlay;
  if (w.state.hud) overlay = hud_overlay(w);
  bool last_frame = w.args.frames && w.frame + 1 >= *w.args.frames;
  bool shoot = w.state.screenshot || (last_frame && !w.args.screenshot.empty());
  w.state.screenshot = false;
  FrameImage shot;
  PresentResult r = present(w.ctx, w.presenter, w.swapchain, w.renderer.color_image(), w.renderer.color_layout(),
                            w.state.hud ? &overlay : nullptr, shoot && w.swapchain.readback ? &shot : nullptr);
  if (shoot && !w.swapchain.readback)  // the window's images cannot be read: the rendered frame instead
    w.renderer.render(fly_camera_desc(w.camera), &shot, w.state.settings);
  if (r == PresentResult::out_of_date) w.state.framebuffer_changed = true;
  if (shoot) keep_screenshot(w, shot, final_shot);
  return last_frame;
}

// --resize-at: shrinks the window to 3/4 and waits until the framebuffer follows.
void scripted_resize(Walk& w) {
  VkExtent2D wanted{std::max(16u, w.desc.width * 3 / 4), std::max(16u, w.desc.height * 3 / 4)};
  glfwSetWindowSize(w.window, int(wanted.width), int(wanted.height));
  wait_for_framebuffer(w.window, wanted);
  w.state.framebuffer_changed = true;
}

void walk_loop(Walk& w, FrameImage& final_shot) {
  while (!glfwWindowShouldClose(w.window)) {
    glfwPollEvents();
    if (!ready_to_present(w)) continue;
    move_camera(w);
    bool last_frame = draw_frame(w, final_shot);
    ++w.frame;
    count_frame(w.fps);
    if (last_frame) break;
    if (w.args.resize_at && w.frame == *w.args.resize_at) scripted_resize(w);
  }
}

// The renderer and the present targets for one walk, its loop, and the closing summary line.
void walk_session(vk::Context& ctx, const WalkArgs& args, const SceneDesc& desc, const Scene& scene, GLFWwindow* window,
                  WalkState& state, FrameImage& final_shot) {
  Renderer renderer(ctx, scene, desc.width, desc.height, desc.samples);
  state.wireframe_available = renderer.has_wireframe();
  CameraPlayback playback = scene_camera_playback(scene);
  state.playback_available = bool(playback.at);
  state.playing = args.play;

  PresentTargets targets{ctx, {}, {}};
  create_presenter(ctx, targets.presenter, renderer.color_image(), kMaxOverlayBytes);
  Walk w{args, desc, scene, window, ctx, renderer, targets.swapchain, targets.presenter, state, std::move(playback)};
  w.camera = fly_camera_from(desc.camera);
  glfwGetCursorPos(window, &w.cursor.x, &w.cursor.y);
  w.start = w.last = clock::now();
  w.fps.start = w.start;
  walk_loop(w, final_shot);
  double seconds = std::chrono::duration<double>(clock::now() - w.start).count();
  std::printf("walk: %u frames in %.2f s (%.1f fps) on %s; swapchain created %u time(s); last frame: %u trees, "
              "%u visible, %u leaves drawn, mean lambda %.3f\n",
              w.frame, seconds, w.frame / std::max(seconds, 1e-9), ctx.properties.deviceName,
              w.swapchain.generation, w.stats.instances, w.stats.branch_draws, w.stats.leaves_drawn,
              w.stats.mean_lambda);
}

}  // namespace

int run_walk(const WalkArgs& args) {
  std::filesystem::path screenshot_path = args.screenshot;
  if (!args.screenshot.empty()) check_output_path(screenshot_path, "--screenshot");
  SceneDesc desc = load_scene_file(args.scene);
  if (args.play && desc.paths.empty()) throw InputError(args.scene, 0, "--play", "the scene has no [[path]] to play");
  override_size(desc, args.width, args.height);
  // Presets come generated and baked from the species cache, as in `forest render`, so the
  // opt mode ([3]) has its tables and a still frame matches `forest render` exactly.
  Scene scene = build_cached_scene(desc, args.scene, "");

  Window win;
  open_window(win, desc, args.scene);
  vk::ContextOptions options = window_context_options(args, win.window);
  WalkState state;
  state.settings = scene_frame_settings(desc);
  if (args.shadows) state.settings.shadows = *args.shadows;
  if (args.impostors) state.settings.impostors = *args.impostors ? ImpostorMode::switched : ImpostorMode::off;
  state.hud = !args.no_hud;
  listen_to_window(win.window, state);

  FrameImage final_shot;
  CommandContext context(options);
  walk_session(context.ctx, args, desc, scene, win.window, state, final_shot);
  // Torn down before the verdict, so that what the teardown reports counts too.
  context.destroy();
  if (validation_failed(context.ctx, "screenshot")) return 1;
  if (!final_shot.rgba.empty()) {
    write_image(final_shot, screenshot_path);
    std::printf("wrote %s (%ux%u)\n", screenshot_path.c_str(), final_shot.width, final_shot.height);
  }
  return 0;
}

}  // namespace forest::app
