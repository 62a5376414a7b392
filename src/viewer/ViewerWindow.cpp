#include "viewer/ViewerWindow.h"

#include <string>

// GLFW declares only what we call; GL comes from libepoxy.
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "core/Errors.h"

namespace raycache {

namespace {

std::string glfwReason() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "unknown reason";
}

}  // namespace

ViewerWindow::ViewerWindow(int width, int height, const char* title, bool vsync) {
    if (!glfwInit())
        throw RuntimeError("cannot open a window (" + glfwReason() + "); is DISPLAY set? Try xvfb-run for no screen");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(width, height, title, nullptr, nullptr);
    if (!window_) {
        const std::string reason = glfwReason();
        glfwTerminate();
        throw RuntimeError("cannot open an OpenGL 3.3 window: " + reason);
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(vsync ? 1 : 0);
    // Installed before ImGui's callbacks, which call it in turn.
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, &ViewerWindow::onKey);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's directory
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
}

ViewerWindow::~ViewerWindow() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
}

bool ViewerWindow::closeRequested() const { return glfwWindowShouldClose(window_); }
void ViewerWindow::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void ViewerWindow::waitEvents(double timeoutSeconds) { glfwWaitEventsTimeout(timeoutSeconds); }
void ViewerWindow::wake() { glfwPostEmptyEvent(); }
void ViewerWindow::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }

void ViewerWindow::onKey(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    static_cast<ViewerWindow*>(glfwGetWindowUserPointer(window))->keyPresses_.push_back(key);
}

std::vector<int> ViewerWindow::takeKeyPresses() {
    std::vector<int> keys;
    keys.swap(keyPresses_);
    return keys;
}

void ViewerWindow::beginUiFrame() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void ViewerWindow::endUiFrame() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void ViewerWindow::swapBuffers() { glfwSwapBuffers(window_); }

}  // namespace raycache
