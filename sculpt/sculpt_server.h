#pragma once
// The HTTP and WebSocket server of `dnurbs serve` (docs/serve.md), on Boost.Beast: it serves the
// sculpting page and a fixed list of three.js files, and at /ws connects clients to one
// SculptSession. The session runs on a simulation thread at a fixed step rate; the network runs
// on the calling thread. Client messages go to the simulation thread through a queue (at most
// kMaxWaitingMessages waiting per client; more are dropped and reported); replies, statuses and
// frames come back through the network thread. A client that falls behind loses frames, and gets
// a frame of every shape next, so it never shows a stale shape.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "dnurbs/sculpt/sculpt_session.h"

namespace dnurbs {

struct SculptServerOptions {
  std::string host = "127.0.0.1";  ///< the address to bind (loopback unless chosen otherwise)
  unsigned short port = 8080;      ///< 0: a free port chosen by the system
  std::filesystem::path web_root;  ///< index.html, app.js, style.css
  std::filesystem::path three_root = "/usr/share/javascript/three";  ///< Debian's libjs-three
  double steps_per_second = 60.0;  ///< simulation ticks a second of wall time
  double statuses_per_second = 10.0;
  /// Larger WebSocket messages close the connection (the session refuses those above its own,
  /// smaller limit with an error reply).
  std::size_t max_message_bytes = 64 * 1024;
  /// Binary frames waiting for a slow client beyond this are dropped (it then gets a full frame).
  std::size_t max_waiting_frames = 3;
};

/// Messages of one client waiting for the simulation thread; more are dropped.
constexpr std::size_t kMaxWaitingMessages = 256;

class SculptServer {
 public:
  /// Binds host:port; throws Error naming the address if it cannot (a bad address, a port in
  /// use) and naming the file if the web root lacks index.html.
  SculptServer(SculptSession& session, SculptServerOptions options);
  ~SculptServer();
  SculptServer(const SculptServer&) = delete;
  SculptServer& operator=(const SculptServer&) = delete;

  /// The bound port (the chosen one when options.port was 0).
  unsigned short port() const;
  /// Serves until SIGINT or SIGTERM (or stop()): then closes every connection, stops the
  /// simulation thread and returns. Throws Error if the simulation thread failed (it stops the
  /// server first).
  void run();
  /// Asks run() to return (thread-safe).
  void stop();

  /// The implementation's shared state (sculpt_server.cpp).
  struct State;

 private:
  std::unique_ptr<State> state_;
};

}  // namespace dnurbs
