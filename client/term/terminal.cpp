#include "term/terminal.hpp"

#include <signal.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <string>

#include "term/keys.hpp"

namespace fts::client::term {

namespace {

termios g_saved{};
volatile sig_atomic_t g_active = 0;
volatile sig_atomic_t g_kitty = 0;
volatile sig_atomic_t g_mouse = 0;
volatile sig_atomic_t g_resized = 0;
volatile sig_atomic_t g_stop = 0;
bool g_atexit_registered = false;

// Leave the alternate screen, show the cursor, reset colours, pop the kitty flags.
constexpr char kRestore[] = "\x1b[0m\x1b[?25h\x1b[?1049l";
constexpr char kKittyPopBytes[] = "\x1b[<u";
constexpr char kMouseOffBytes[] = "\x1b[?1004l\x1b[?1006l\x1b[?1003l";

void raw_write(const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(STDOUT_FILENO, data, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return;
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
}

void on_stop(int sig) { g_stop = sig; }
void on_winch(int) { g_resized = 1; }

void on_crash(int sig) {
  leave();
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install(int sig, void (*handler)(int), int flags) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = flags;
  ::sigaction(sig, &sa, nullptr);
}

}  // namespace

bool enter(bool kitty_keys, bool mouse) {
  if (g_active) return true;
  if (!::isatty(STDIN_FILENO) || !::isatty(STDOUT_FILENO)) return false;
  if (::tcgetattr(STDIN_FILENO, &g_saved) != 0) return false;
  termios raw = g_saved;
  // Raw input: no echo, no line buffering, no signals from keys (Ctrl-C arrives as a
  // byte and quits cleanly), no CR/NL translation; reads return what is there.
  raw.c_iflag &= ~static_cast<tcflag_t>(BRKINT | ICRNL | INPCK | ISTRIP | IXON);
  raw.c_oflag &= ~static_cast<tcflag_t>(OPOST);
  raw.c_cflag |= CS8;
  raw.c_lflag &= ~static_cast<tcflag_t>(ECHO | ICANON | IEXTEN | ISIG);
  raw.c_cc[VMIN] = 0;
  raw.c_cc[VTIME] = 0;
  if (::tcsetattr(STDIN_FILENO, TCSAFLUSH, &raw) != 0) return false;
  g_active = 1;
  if (!g_atexit_registered) {
    std::atexit([] { leave(); });
    g_atexit_registered = true;
  }
  install(SIGINT, on_stop, 0);
  install(SIGTERM, on_stop, 0);
  install(SIGHUP, on_stop, 0);
  install(SIGWINCH, on_winch, SA_RESTART);
  install(SIGSEGV, on_crash, SA_RESETHAND);
  install(SIGABRT, on_crash, SA_RESETHAND);
  install(SIGBUS, on_crash, SA_RESETHAND);
  install(SIGFPE, on_crash, SA_RESETHAND);
  // Alternate screen, hidden cursor, cleared; the kitty query (no push yet), the mouse.
  g_mouse = mouse ? 1 : 0;
  write_all(enter_bytes(kitty_keys, mouse));
  return true;
}

void push_kitty() {
  if (!g_active || g_kitty) return;
  g_kitty = 1;
  write_all(kitty_push() + std::string(kKittyQuery));
}

void note_hangup() { g_stop = SIGHUP; }

void leave() {
  if (!g_active) return;
  g_active = 0;
  if (g_kitty) raw_write(kKittyPopBytes, sizeof kKittyPopBytes - 1);
  if (g_mouse) raw_write(kMouseOffBytes, sizeof kMouseOffBytes - 1);
  raw_write(kRestore, sizeof kRestore - 1);
  ::tcsetattr(STDIN_FILENO, TCSAFLUSH, &g_saved);
}

TerminalSize size() {
  winsize ws{};
  if (::ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 && ws.ws_row > 0)
    return {ws.ws_col, ws.ws_row};
  return {80, 24};
}

bool take_resized() {
  if (!g_resized) return false;
  g_resized = 0;
  return true;
}

int stop_signal() { return g_stop; }

void write_all(std::string_view bytes) { raw_write(bytes.data(), bytes.size()); }

}  // namespace fts::client::term
