// forest walk: the scene in a window. The renderer draws into its own image exactly as for
// `forest render`; the present step (engine/present/present.h) copies it to the swapchain with
// the HUD on top. Keys switch prune modes and views; WASD + mouse fly the camera.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "engine/tools/bake/species_cache.h"
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
    case GLFW_KEY_1: s.settings.prune_mode = PRUNE_FULL; break;
    case GLFW_KEY_2: s.settings.prune_mode = PRUNE_COOK; break;
    case GLFW_KEY_3: s.settings.prune_mode = PRUNE_OPT; break;
    case GLFW_KEY_O: s.settings.occlusion = !s.settings.occlusion; break;
    case GLFW_KEY_L: s.settings.lambda_view = !s.settings.lambda_view; break;
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

const char* prune_name(uint32_t mode) {
  switch (mode) {
    case PRUNE_FULL: return "full";
    case PRUNE_COOK: return "cook";
    case PRUNE_OPT: return "opt";
    default: return "fixed";
  }
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
      format("[1-3] prune %s  [L] %s  [F] wire %s", prune_name(f.prune_mode), f.lambda_view ? "lambda" : "shaded",
             f.wireframe ? "on" : "off"),
      format("[O] occlusion %s (%u culled)  [P] path %s", f.occlusion ? "on" : "off", st.occluded_instances,
             !s.playback_available ? "none" : s.playing ? "playing" : "stopped"),
      format("%.0f %.0f %.0f  %.1f m/s  [C] shot", cam.position.x, cam.position.y, cam.position.z, cam.speed),
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

}  // namespace

int run_walk(const WalkArgs& args) {
  using clock = std::chrono::steady_clock;
  std::filesystem::path screenshot_path = args.screenshot;
  if (!args.screenshot.empty()) check_output_path(screenshot_path, "--screenshot");
  SceneDesc desc = load_scene_file(args.scene);
  if (args.play && desc.paths.empty()) throw InputError(args.scene, 0, "--play", "the scene has no [[path]] to play");
  if (args.width) desc.width = *args.width;
  if (args.height) desc.height = *args.height;
  // Presets come generated and baked from the species cache, as in `forest render`, so the
  // opt mode ([3]) has its tables and a still frame matches `forest render` exactly.
  SpeciesCacheOptions cache;
  cache.log = [](const std::string& line) { std::printf("%s\n", line.c_str()), std::fflush(stdout); };
  SceneBuildOptions build;
  build.species = cached_species_source(cache);
  Scene scene = build_scene(desc, build);
  if (scene.placement_shortfall > 0)
    std::fprintf(stderr, "forest: %s: placement: only %u of %u trees found room (min_spacing / radius / max_slope)\n",
                 args.scene.c_str(), desc.placement.count - scene.placement_shortfall, desc.placement.count);

  glfwSetErrorCallback(on_glfw_error);
  Window win;
  if (!glfwInit())
    throw vk::VkFailure("cannot open a window: " + glfw_error + " (no display? run under xvfb-run)");
  if (!glfwVulkanSupported()) throw vk::VkFailure("cannot open a window: GLFW finds no Vulkan loader");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  std::string title = "forest walk - " + args.scene;
  win.window = glfwCreateWindow(int(desc.width), int(desc.height), title.c_str(), nullptr, nullptr);
  if (!win.window) throw vk::VkFailure("cannot open a window: " + glfw_error);
  GLFWwindow* window = win.window;

  vk::Context ctx;
  vk::ContextOptions options;
  options.device = args.device;
  options.validation = args.validate || vk::validation_from_env();
  uint32_t glfw_extension_count = 0;
  const char** glfw_extensions = glfwGetRequiredInstanceExtensions(&glfw_extension_count);
  options.instance_extensions.assign(glfw_extensions, glfw_extensions + glfw_extension_count);
  options.create_surface = [window](VkInstance instance) {
    VkSurfaceKHR surface;
    VK_CHECK(glfwCreateWindowSurface(instance, window, nullptr, &surface));
    return surface;
  };

  WalkState state;
  state.settings = scene_frame_settings(desc);
  state.hud = !args.no_hud;
  glfwSetWindowUserPointer(window, &state);
  glfwSetKeyCallback(window, on_key);
  glfwSetScrollCallback(window, on_scroll);
  glfwSetFramebufferSizeCallback(window, on_framebuffer_size);

  int code = 0;
  FrameImage final_shot;
  try {
    vk::create_context(ctx, options);
    Renderer renderer(ctx, scene, desc.width, desc.height, desc.samples);
    state.wireframe_available = renderer.has_wireframe();
    CameraPlayback playback = scene_camera_playback(scene);
    state.playback_available = bool(playback.at);
    state.playing = args.play;

    PresentTargets targets{ctx, {}, {}};
    vk::Swapchain& swapchain = targets.swapchain;
    Presenter& presenter = targets.presenter;
    create_presenter(ctx, presenter, renderer.color_image(), kMaxOverlayBytes);
    bool hud_bgra = false;
    bool have_swapchain = false;
    FlyCamera camera = fly_camera_from(desc.camera);
    glm::dvec2 cursor{0.0};
    glfwGetCursorPos(window, &cursor.x, &cursor.y);
    double play_time = 0.0;
    FrameStats stats;
    uint32_t frame = 0, shots = 0;
    auto start = clock::now(), last = start, fps_start = start;
    uint32_t fps_frames = 0;
    double fps = 0.0, cpu_ms = 0.0;

    while (!glfwWindowShouldClose(window)) {
      glfwPollEvents();
      VkExtent2D fb = framebuffer_extent(window);
      if (fb.width == 0 || fb.height == 0) {  // minimized: nothing to present to
        glfwWaitEvents();
        continue;
      }
      if (!have_swapchain || state.framebuffer_changed) {
        state.framebuffer_changed = false;
        have_swapchain = vk::create_swapchain(ctx, swapchain, fb);
        if (!have_swapchain) continue;
        std::string why;
        bool blit = can_present(ctx, renderer.color_image().format, swapchain.format, &why);
        if (args.present == "blit" && !blit) throw vk::VkFailure("--present blit: " + why);
        bool pass = args.present == "pass" || !blit;
        if (pass && !presenter.copy_pass && args.present != "pass")
          std::fprintf(stderr, "forest: %s; using the copy pass\n", why.c_str());
        presenter.copy_pass = pass;
        if (!overlay_byte_order(swapchain.format, &hud_bgra)) state.hud = false;  // HUD needs 8-bit RGBA/BGRA
      }

      auto now = clock::now();
      double dt = args.frames ? kScriptedStep : std::chrono::duration<double>(now - last).count();
      last = now;
      state.now = std::chrono::duration<double>(now - start).count();
      FlyInput input = keyboard_and_mouse(window, cursor);
      input.speed_steps = float(state.wheel);
      state.wheel = 0.0;
      if (args.fly) {  // scripted: forward while turning slowly right
        input.forward = 1.0f;
        input.look_x = 4.0f;
      }
      if (state.playing) {
        play_time += dt;
        FlyCamera from_path = fly_camera_from(playback.at(play_time));
        from_path.speed = camera.speed;
        from_path.moved = true;
        camera = from_path;
      } else {
        fly_update(camera, input, float(dt), &scene.terrain);
      }

      if (state.freeze_lod && !state.settings.lod_camera) state.settings.lod_camera = camera.position;
      stats = renderer.render(fly_camera_desc(camera), nullptr, state.settings);

      OverlayImage overlay;
      if (state.hud) {
        uint32_t scale = swapchain.extent.height >= 1000 ? 2 : 1;
        overlay = draw_text_panel(hud_lines(state, stats, camera, fps, cpu_ms, ctx.properties.deviceName), scale, hud_bgra);
        if (overlay.bytes.size() > kMaxOverlayBytes) overlay = {};
      }
      bool last_frame = args.frames && frame + 1 >= *args.frames;
      bool shoot = state.screenshot || (last_frame && !args.screenshot.empty());
      state.screenshot = false;
      FrameImage shot;
      PresentResult r = present(ctx, presenter, swapchain, renderer.color_image(), renderer.color_layout(),
                                state.hud ? &overlay : nullptr, shoot && swapchain.readback ? &shot : nullptr);
      if (shoot && !swapchain.readback)  // the window's images cannot be read: the rendered frame instead
        renderer.render(fly_camera_desc(camera), &shot, state.settings);
      if (r == PresentResult::out_of_date) state.framebuffer_changed = true;

      if (shoot && args.frames) {
        final_shot = std::move(shot);  // written after the validation check below
      } else if (shoot) {
        std::filesystem::path p = screenshot_path.empty() ? std::filesystem::path(format("forest_walk_%03u.png", shots))
                                                          : screenshot_path;
        write_image(shot, p);
        ++shots;
        say(state, "wrote " + p.string());
      }

      ++frame;
      ++fps_frames;
      double window_s = std::chrono::duration<double>(clock::now() - fps_start).count();
      if (window_s >= 0.5) {  // HUD numbers over half-second windows: readable, still current
        fps = fps_frames / window_s;
        cpu_ms = 1000.0 * window_s / fps_frames;
        fps_start = clock::now();
        fps_frames = 0;
      }
      if (last_frame) break;
      if (args.resize_at && frame == *args.resize_at) {
        VkExtent2D wanted{std::max(16u, desc.width * 3 / 4), std::max(16u, desc.height * 3 / 4)};
        glfwSetWindowSize(window, int(wanted.width), int(wanted.height));
        wait_for_framebuffer(window, wanted);
        state.framebuffer_changed = true;
      }
    }
    double seconds = std::chrono::duration<double>(clock::now() - start).count();
    std::printf("walk: %u frames in %.2f s (%.1f fps) on %s; swapchain created %u time(s); last frame: %u trees, "
                "%u visible, %u leaves drawn, mean lambda %.3f\n",
                frame, seconds, frame / std::max(seconds, 1e-9), ctx.properties.deviceName, swapchain.generation,
                stats.instances, stats.branch_draws, stats.leaves_drawn, stats.mean_lambda);
  } catch (...) {
    vk::destroy_context(ctx);
    throw;
  }
  vk::destroy_context(ctx);
  if (ctx.validation_messages > 0) {
    std::fprintf(stderr, "forest: %u Vulkan validation message(s); no screenshot written\n",
                 ctx.validation_messages.load());
    code = 1;
  } else if (!final_shot.rgba.empty()) {
    write_image(final_shot, screenshot_path);
    std::printf("wrote %s (%ux%u)\n", screenshot_path.c_str(), final_shot.width, final_shot.height);
  }
  return code;
}

}  // namespace forest::app
