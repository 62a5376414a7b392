#pragma once
// The viewer's window: a GLFW window with an OpenGL 3.3 core context and
// Dear ImGui on it, set up and torn down in one place. Lives on the UI
// thread (GLFW and GL calls must stay there); wake() is the exception.
#include <vector>

struct GLFWwindow;

namespace raycache {

class ViewerWindow {
public:
    // Opens a width x height window. Throws RuntimeError (naming GLFW's
    // reason) when there is no display or no OpenGL 3.3.
    ViewerWindow(int width, int height, const char* title, bool vsync);
    ~ViewerWindow();
    ViewerWindow(const ViewerWindow&) = delete;
    ViewerWindow& operator=(const ViewerWindow&) = delete;

    GLFWwindow* handle() const { return window_; }
    bool closeRequested() const;
    void requestClose();
    // Waits for input, a wake() or the timeout, whichever comes first.
    void waitEvents(double timeoutSeconds);
    // Wakes waitEvents from any thread.
    static void wake();
    void framebufferSize(int& width, int& height) const;
    // Keys pressed (GLFW key codes) since the last call, in order. Recorded
    // as events arrive, so a press and release within one UI frame (a quick
    // tap) is not lost, as it would be by polling key state.
    std::vector<int> takeKeyPresses();

    // ImGui frame brackets; endFrame draws the UI into the current framebuffer.
    void beginUiFrame();
    void endUiFrame();
    void swapBuffers();

private:
    static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);

    GLFWwindow* window_ = nullptr;
    std::vector<int> keyPresses_;
};

}  // namespace raycache
