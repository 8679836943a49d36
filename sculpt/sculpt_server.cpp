#include "dnurbs/sculpt/sculpt_server.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <deque>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using Clock = std::chrono::steady_clock;

constexpr std::size_t kMaxRequestBytes = 8 * 1024;
constexpr auto kHttpTimeout = std::chrono::seconds(30);
constexpr auto kShutdownGrace = std::chrono::milliseconds(500);

// One message for a client: shared by every client it is broadcast to.
struct Outgoing {
  std::shared_ptr<const std::string> data;
  bool binary = false;
};

std::shared_ptr<const std::string> shared(std::string text) {
  return std::make_shared<const std::string>(std::move(text));
}

// The file a GET target names: the page's files (plain names in the web root) and the two
// three.js modules it imports; nothing else.
std::optional<std::pair<std::filesystem::path, const char*>> static_file(
    std::string_view target, const SculptServerOptions& options) {
  target = target.substr(0, target.find('?'));
  if (target == "/" || target == "/index.html") {
    return std::make_pair(options.web_root / "index.html", "text/html; charset=utf-8");
  }
  if (target == "/three/build/three.module.js" ||
      target == "/three/examples/jsm/controls/OrbitControls.js") {
    return std::make_pair(options.three_root / std::string(target.substr(7)),
                          "text/javascript; charset=utf-8");
  }
  const std::string_view name = target.substr(1);
  const bool plain = target.size() > 1 && target.size() < 64 && target.front() == '/' &&
                     name.front() != '.' && std::all_of(name.begin(), name.end(), [](char c) {
                       return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                              (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
                     });
  if (plain && name.ends_with(".js")) {
    return std::make_pair(options.web_root / std::string(name), "text/javascript; charset=utf-8");
  }
  if (plain && name.ends_with(".css")) {
    return std::make_pair(options.web_root / std::string(name), "text/css; charset=utf-8");
  }
  return std::nullopt;
}

}  // namespace

class WebSocketConnection;

// Everything the server shares between its connections and its two threads.
struct SculptServer::State {
  State(SculptSession& s, SculptServerOptions o)
      : session(s),
        options(std::move(o)),
        acceptor(context),
        signals(context, SIGINT, SIGTERM),
        shutdown_timer(context) {}

  // Network thread ------------------------------------------------------------------------------
  void accept();
  void shutdown();
  http::response<http::string_body> respond(const http::request<http::string_body>& request) const;
  bool origin_allowed(const http::request<http::string_body>& request) const;
  void joined(const std::shared_ptr<WebSocketConnection>& connection);  // accepted handshake
  void left(const std::shared_ptr<WebSocketConnection>& connection);    // read failed or closed
  void received(const std::shared_ptr<WebSocketConnection>& connection, std::string text);
  void post_to(const std::shared_ptr<WebSocketConnection>& connection, Outgoing message);
  void broadcast(Outgoing message);

  // Simulation thread ---------------------------------------------------------------------------
  void simulate();
  // One tick: the clients' messages, a step, the frame, the status when due
  void tick(double now, Clock::time_point& next_status, Clock::duration status_period);
  void handle_events(double now);
  std::string failure;  // written by the simulation thread before it stops, read after join

  SculptSession& session;
  SculptServerOptions options;
  asio::io_context context;
  tcp::acceptor acceptor;
  asio::signal_set signals;
  asio::steady_timer shutdown_timer;
  std::set<std::shared_ptr<WebSocketConnection>> connections;  // network thread only
  std::atomic<bool> running{true};
  std::thread simulation;
  Clock::time_point start = Clock::now();

  // Events for the simulation thread: a join (text empty, joining), a message, a leave.
  struct Event {
    std::shared_ptr<WebSocketConnection> connection;
    enum Kind { kJoin, kMessage, kLeave } kind = kMessage;
    std::string text;
  };
  std::mutex events_mutex;
  std::vector<Event> events;
  std::map<std::shared_ptr<WebSocketConnection>, int> clients;  // simulation thread only
};

class WebSocketConnection : public std::enable_shared_from_this<WebSocketConnection> {
 public:
  WebSocketConnection(tcp::socket socket, SculptServer::State& state)
      : stream_(std::move(socket)), state_(state) {}

  void start(const http::request<http::string_body>& request) {
    stream_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    stream_.read_message_max(state_.options.max_message_bytes);
    stream_.async_accept(request, [self = shared_from_this()](beast::error_code error) {
      if (!error) {
        self->state_.joined(self);
        self->read();
      }
    });
  }

  // Network thread: queue a message; a slow client's oldest waiting frame is dropped.
  void send(Outgoing message) {
    if (closed_) {
      return;
    }
    if (message.binary) {
      const auto waiting = std::count_if(queue_.begin() + (writing_ ? 1 : 0), queue_.end(),
                                         [](const Outgoing& m) { return m.binary; });
      if (static_cast<std::size_t>(waiting) >= state_.options.max_waiting_frames) {
        const auto oldest = std::find_if(queue_.begin() + (writing_ ? 1 : 0), queue_.end(),
                                         [](const Outgoing& m) { return m.binary; });
        queue_.erase(oldest);
        needs_full_frame.store(true);
      }
    }
    queue_.push_back(std::move(message));
    if (!writing_) {
      write();
    }
  }

  void close() {
    if (closed_) {
      return;
    }
    closed_ = true;
    stream_.async_close(websocket::close_code::going_away,
                        [self = shared_from_this()](beast::error_code) {});
  }

  std::atomic<bool> needs_full_frame{false};
  std::atomic<std::size_t> waiting{0};  // messages queued for the simulation thread
  std::atomic<std::size_t> dropped{0};  // messages dropped since the last report
  double last_drop_report = -1e300;     // simulation thread only

 private:
  void read() {
    stream_.async_read(buffer_, [self = shared_from_this()](beast::error_code error, std::size_t) {
      if (error) {
        self->closed_ = true;
        self->state_.left(self);
        return;
      }
      if (self->stream_.got_text()) {
        self->state_.received(self, beast::buffers_to_string(self->buffer_.data()));
      } else {
        self->send({shared(R"({"type":"error","message":"expected a text message (JSON), got )"
                           R"(a binary one","request":""})"),
                    false});
      }
      self->buffer_.consume(self->buffer_.size());
      self->read();
    });
  }

  void write() {
    writing_ = true;
    stream_.binary(queue_.front().binary);
    stream_.async_write(asio::buffer(*queue_.front().data),
                        [self = shared_from_this()](beast::error_code error, std::size_t) {
                          self->writing_ = false;
                          if (error) {
                            self->queue_.clear();
                            return;
                          }
                          self->queue_.pop_front();
                          if (!self->queue_.empty() && !self->closed_) {
                            self->write();
                          }
                        });
  }

  websocket::stream<beast::tcp_stream> stream_;
  SculptServer::State& state_;
  beast::flat_buffer buffer_;
  std::deque<Outgoing> queue_;
  bool writing_ = false;
  bool closed_ = false;
};

// One HTTP connection: static files, or the upgrade to a WebSocket at /ws.
class HttpConnection : public std::enable_shared_from_this<HttpConnection> {
 public:
  HttpConnection(tcp::socket socket, SculptServer::State& state)
      : stream_(std::move(socket)), state_(state) {}

  void read() {
    parser_.emplace();
    parser_->header_limit(kMaxRequestBytes);
    parser_->body_limit(kMaxRequestBytes);
    stream_.expires_after(kHttpTimeout);
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code error, std::size_t) {
                       if (error) {
                         self->reply_error(error);
                         return;
                       }
                       self->dispatch(self->parser_->release());
                     });
  }

 private:
  // The handshake's response is built from the request when the accept starts (Beast's
  // accept_op), so the request need not outlive this call.
  void dispatch(const http::request<http::string_body>& request) {
    if (websocket::is_upgrade(request) && request.target() == "/ws" &&
        state_.origin_allowed(request)) {
      stream_.expires_never();
      std::make_shared<WebSocketConnection>(stream_.release_socket(), state_)->start(request);
      return;
    }
    if (websocket::is_upgrade(request)) {
      auto response = std::make_shared<http::response<http::string_body>>(
          request.target() == "/ws" ? http::status::forbidden : http::status::not_found,
          request.version());
      response->body() = request.target() == "/ws" ? "origin not allowed\n" : "not found\n";
      response->prepare_payload();
      response->keep_alive(false);
      send(std::move(response));
      return;
    }
    send(std::make_shared<http::response<http::string_body>>(state_.respond(request)));
  }

  void send(std::shared_ptr<http::response<http::string_body>> response) {
    response_ = std::move(response);
    http::async_write(stream_, *response_,
                      [self = shared_from_this()](beast::error_code error, std::size_t) {
                        if (error || !self->response_->keep_alive()) {
                          beast::error_code ignored;
                          self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
                          return;
                        }
                        self->read();
                      });
  }

  // A request too large or malformed gets 400 (413 for size); a closed connection nothing.
  void reply_error(beast::error_code error) {
    if (error == http::error::end_of_stream || error == beast::error::timeout ||
        error == asio::error::operation_aborted) {
      return;
    }
    const bool too_large = error == http::error::header_limit || error == http::error::body_limit;
    auto response = std::make_shared<http::response<http::string_body>>(
        too_large ? http::status::payload_too_large : http::status::bad_request, 11);
    response->body() = too_large ? "request too large\n" : "bad request\n";
    response->keep_alive(false);
    response->prepare_payload();
    send(std::move(response));
  }

  beast::tcp_stream stream_;
  SculptServer::State& state_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<http::response<http::string_body>> response_;
};

void SculptServer::State::accept() {
  acceptor.async_accept([this](beast::error_code error, tcp::socket socket) {
    if (error) {
      return;  // the acceptor was closed
    }
    std::make_shared<HttpConnection>(std::move(socket), *this)->read();
    accept();
  });
}

http::response<http::string_body> SculptServer::State::respond(
    const http::request<http::string_body>& request) const {
  http::response<http::string_body> response(http::status::ok, request.version());
  response.keep_alive(request.keep_alive());
  const std::string_view target(request.target().data(), request.target().size());
  const auto file = static_file(target, options);
  std::string body;
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    response.result(http::status::method_not_allowed);
    body = "only GET and HEAD\n";
  } else if (target == "/favicon.ico") {
    response.result(http::status::no_content);
  } else if (std::ifstream in(file ? file->first : std::filesystem::path(), std::ios::binary);
             file && in) {
    std::ostringstream contents;
    contents << in.rdbuf();
    body = contents.str();
    response.set(http::field::content_type, file->second);
    response.set(http::field::cache_control, "no-cache");
  } else {
    response.result(http::status::not_found);
    body = "not found\n";
  }
  if (request.method() != http::verb::head) {
    response.body() = std::move(body);
  }
  response.prepare_payload();
  return response;
}

bool SculptServer::State::origin_allowed(const http::request<http::string_body>& request) const {
  // A page of another site open in the user's browser must not sculpt (or save) through the
  // user's server: a browser's handshake names its page's origin, which must be this server.
  const auto origin = request.find(http::field::origin);
  if (origin == request.end()) {
    return true;  // not a browser
  }
  const auto host = request.find(http::field::host);
  return host != request.end() && origin->value() == "http://" + std::string(host->value());
}

void SculptServer::State::joined(const std::shared_ptr<WebSocketConnection>& connection) {
  const std::lock_guard lock(events_mutex);
  events.push_back({connection, Event::kJoin, {}});
}

void SculptServer::State::left(const std::shared_ptr<WebSocketConnection>& connection) {
  connections.erase(connection);
  const std::lock_guard lock(events_mutex);
  events.push_back({connection, Event::kLeave, {}});
}

void SculptServer::State::received(const std::shared_ptr<WebSocketConnection>& connection,
                                   std::string text) {
  if (connection->waiting.load() >= kMaxWaitingMessages) {
    ++connection->dropped;
    return;
  }
  ++connection->waiting;
  const std::lock_guard lock(events_mutex);
  events.push_back({connection, Event::kMessage, std::move(text)});
}

void SculptServer::State::post_to(const std::shared_ptr<WebSocketConnection>& connection,
                                  Outgoing message) {
  asio::post(context, [connection, message = std::move(message)] { connection->send(message); });
}

void SculptServer::State::broadcast(Outgoing message) {
  asio::post(context, [this, message = std::move(message)] {
    for (const auto& connection : connections) {
      connection->send(message);
    }
  });
}

void SculptServer::State::handle_events(double now) {
  std::vector<Event> batch;
  {
    const std::lock_guard lock(events_mutex);
    batch.swap(events);
  }
  for (Event& event : batch) {
    const auto client = clients.find(event.connection);
    if (event.kind == Event::kJoin) {
      const int id = session.connect();
      clients[event.connection] = id;
      auto scene = shared(session.scene_message(id));
      auto frame = shared(session.full_frame());
      asio::post(context, [this, connection = event.connection, scene, frame] {
        connections.insert(connection);
        connection->send({scene, false});
        connection->send({frame, true});
      });
      broadcast({shared(session.status_message(now)), false});
    } else if (event.kind == Event::kLeave && client != clients.end()) {
      session.disconnect(client->second);
      clients.erase(client);
      broadcast({shared(session.status_message(now)), false});
    } else if (event.kind == Event::kMessage && client != clients.end()) {
      --event.connection->waiting;
      // Dropped messages are reported once a second at most, as the session reports a flood
      if (event.connection->dropped.load() > 0 && now - event.connection->last_drop_report >= 1.0) {
        event.connection->last_drop_report = now;
        const std::size_t dropped = event.connection->dropped.exchange(0);
        post_to(event.connection,
                {shared(R"({"type":"error","request":"","message":")" + std::to_string(dropped) +
                        " messages dropped: more than " + std::to_string(kMaxWaitingMessages) +
                        R"( were waiting"})"),
                 false});
      }
      SculptReply reply = session.handle(client->second, event.text, now);
      for (std::string& message : reply.messages) {
        post_to(event.connection, {shared(std::move(message)), false});
      }
      if (reply.status_changed) {
        broadcast({shared(session.status_message(now)), false});
      }
    }
  }
}

void SculptServer::State::simulate() {
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / options.steps_per_second));
  const auto status_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / options.statuses_per_second));
  auto next = Clock::now();
  auto next_status = next;
  while (running.load()) {
    const double now = std::chrono::duration<double>(Clock::now() - start).count();
    try {
      tick(now, next_status, status_period);
    } catch (const std::exception& error) {
      // Nothing a client sends gets here (the session answers it); this is a fault of the
      // server itself: stop, and let run() report it
      failure = error.what();
      asio::post(context, [this] { shutdown(); });
      return;
    }
    next += period;
    // Behind by more than a tick (a slow step): do not try to catch up with a burst
    next = std::max(next, Clock::now() - period);
    std::this_thread::sleep_until(next);
  }
}

void SculptServer::State::tick(double now, Clock::time_point& next_status,
                               Clock::duration status_period) {
  handle_events(now);
  session.tick(now);
  if (std::string frame = session.next_frame(now); !frame.empty()) {
    broadcast({shared(std::move(frame)), true});
  }
  for (const auto& [connection, id] : clients) {
    if (connection->needs_full_frame.exchange(false)) {
      post_to(connection, {shared(session.full_frame()), true});
    }
  }
  if (Clock::now() >= next_status) {
    broadcast({shared(session.status_message(now)), false});
    next_status += status_period;
    next_status = std::max(next_status, Clock::now());
  }
}

void SculptServer::State::shutdown() {
  if (!running.exchange(false)) {
    return;
  }
  signals.cancel();
  beast::error_code ignored;
  acceptor.close(ignored);
  for (const auto& connection : connections) {
    connection->close();
  }
  shutdown_timer.expires_after(kShutdownGrace);
  shutdown_timer.async_wait([this](beast::error_code) { context.stop(); });
}

SculptServer::SculptServer(SculptSession& session, SculptServerOptions options)
    : state_(std::make_unique<State>(session, std::move(options))) {
  const SculptServerOptions& o = state_->options;
  if (!std::filesystem::is_regular_file(o.web_root / "index.html")) {
    throw make_error("the page ", (o.web_root / "index.html").string(), " is missing (web root ",
                     o.web_root.string(), ")");
  }
  if (!(o.steps_per_second > 0.0 && o.steps_per_second <= 1000.0)) {
    throw make_error("steps_per_second ", o.steps_per_second, " is outside (0, 1000]");
  }
  beast::error_code error;
  const asio::ip::address address = asio::ip::make_address(o.host, error);
  if (error) {
    throw make_error("host \"", o.host, "\" is not an IP address: ", error.message());
  }
  const tcp::endpoint endpoint(address, o.port);
  tcp::acceptor& acceptor = state_->acceptor;
  acceptor.open(endpoint.protocol(), error);
  if (!error) {
    acceptor.set_option(asio::socket_base::reuse_address(true), error);
  }
  if (!error) {
    acceptor.bind(endpoint, error);
  }
  if (!error) {
    acceptor.listen(asio::socket_base::max_listen_connections, error);
  }
  if (error) {
    throw make_error("cannot listen on ", o.host, ":", o.port, ": ", error.message());
  }
}

SculptServer::~SculptServer() {
  stop();
  if (state_->simulation.joinable()) {
    state_->simulation.join();
  }
}

unsigned short SculptServer::port() const {
  return state_->acceptor.local_endpoint().port();
}

void SculptServer::run() {
  State& state = *state_;
  state.signals.async_wait([&state](beast::error_code error, int) {
    if (!error) {
      state.shutdown();
    }
  });
  state.accept();
  state.simulation = std::thread([&state] { state.simulate(); });
  state.context.run();
  state.running.store(false);
  state.simulation.join();
  if (!state.failure.empty()) {
    throw make_error("the simulation thread stopped: ", state.failure);
  }
}

void SculptServer::stop() {
  asio::post(state_->context, [state = state_.get()] { state->shutdown(); });
}

}  // namespace dnurbs
