#ifndef bender_HeadlessDisplay_h
#define bender_HeadlessDisplay_h

// The X display that Debian's VTK needs to render off screen, for the headless commands
// (bender-cli render, bender --demo --headless): the process's own DISPLAY, or a private Xvfb
// started for the life of the process. Kept at the application's edge: the modules render
// on whatever display DISPLAY names and never start servers or change the environment.

#include <string>

namespace bender
{

/// Nothing when DISPLAY is set; otherwise starts a private Xvfb (display :91 to :139, the
/// first free one; 1280x1024x24, no TCP) once per process and sets DISPLAY to it. Returns an
/// empty string when rendering can go on, else the one-line reason (Xvfb not installed, or no
/// server could be started). Thread-safe; the server is stopped when the process exits.
std::string EnsureHeadlessDisplay();

} // namespace bender

#endif
