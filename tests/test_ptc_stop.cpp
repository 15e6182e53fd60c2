// Ctrl-C during a PTC request (issue #44, finding 6): the request in flight ends within 0.5 s of
// the stop flag going up, not at its deadline; a request started while the flag is up (a
// program's clean-up: ending a signature session) runs as any other. In the process (PtcClient
// with a flag) and end to end ('hesai listen --sensor' and SIGINT).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "hesai/ptc.h"
#include "hesai_port/net/ptc_client.h"
#include "hesai_port/net/ptc_server.h"
#include "sensor_support.h"
#include "udp_support.h"

namespace {

using hesai::port::PtcClient;
using hesai::port::PtcOutcome;
using hesai::port::PtcResult;
using namespace hesai_test::sensor;

#if defined(HESAI_CLI_EMULATOR)
const double kSlack = 3.0;  // qemu-user starts and ends the program slowly
#else
const double kSlack = 0.5;
#endif

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A TCP port whose kernel accepts connections (the listen backlog) and which never answers.
class SilentUnit {
 public:
  SilentUnit() {
    fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof sa;
    if (bind(fd_, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) == 0 && listen(fd_, 8) == 0 &&
        getsockname(fd_, reinterpret_cast<sockaddr*>(&sa), &len) == 0)
      port_ = ntohs(sa.sin_port);
  }
  ~SilentUnit() { close(fd_); }
  int port() const { return port_; }
  /// Waits (at most 10 s) for a client to connect: true once one has.
  bool accepted() {
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, 10000) != 1) return false;
    const int c = accept(fd_, nullptr, nullptr);
    if (c < 0) return false;
    held_.push_back(c);
    return true;
  }

 private:
  int fd_ = -1, port_ = 0;
  std::vector<int> held_;
};

TEST(SensorStop, TheRequestInFlightEndsWhenTheFlagGoesUp) {
  SilentUnit unit;
  ASSERT_NE(unit.port(), 0);
  std::atomic<bool> stop{false};
  PtcClient client("127.0.0.1", static_cast<std::uint16_t>(unit.port()), 10000);
  client.set_stop(&stop);
  std::thread raise([&] {
    if (unit.accepted()) usleep(200000);
    stop = true;
  });
  std::vector<std::uint8_t> response;
  const auto t0 = std::chrono::steady_clock::now();
  const PtcResult r = client.request(hesai::ptc::Command::inventory, {}, response);
  const double took = seconds_since(t0);
  raise.join();
  EXPECT_EQ(r.outcome, PtcOutcome::stopped) << r.message;
  EXPECT_NE(r.message.find("interrupted during the response header"), std::string::npos) << r.message;
  EXPECT_LT(took, 0.2 + 0.5) << r.message;  // not the 10 s deadline
}

TEST(SensorStop, ARequestStartedWhileTheFlagIsUpRuns) {
  // The stand-in's PTC service, plain TCP, in this process.
  hesai::port::PtcServer server;
  hesai::port::StandInContent content;
  content.model = hesai::Model::pandar64;
  std::string error;
  ASSERT_TRUE(server.open("127.0.0.1", 0, content, error)) << error;
  std::thread serving([&] { server.run(); });
  std::atomic<bool> stop{true};
  PtcClient client("127.0.0.1", server.port(), 3000);
  client.set_stop(&stop);
  std::vector<std::uint8_t> response;
  const PtcResult r = client.request(hesai::ptc::Command::inventory, {}, response);
  server.stop();
  serving.join();
  EXPECT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(std::string(response.begin(), response.begin() + (response.size() < 7 ? 0 : 7)), "STANDIN");
  // A silent unit, the flag up from the start: the request runs to its deadline.
  SilentUnit unit;
  PtcClient silent("127.0.0.1", static_cast<std::uint16_t>(unit.port()), 600);
  silent.set_stop(&stop);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(silent.request(hesai::ptc::Command::inventory, {}, response).outcome, PtcOutcome::timeout);
  EXPECT_GE(seconds_since(t0), 0.55);
}

// 'listen --sensor' against a unit that accepts and never answers, with a PTC timeout of 20 s:
// SIGINT while it waits for the inventory ends the program within 0.5 s.
TEST(SensorStop, CtrlCDuringListensPtcRequestEndsTheProgramAtOnce) {
  SilentUnit unit;
  ASSERT_NE(unit.port(), 0);
  const std::string err = temp_path("stop_listen_err");
  const std::string cmd = "exec env -u HESAI_SECRET -u HESAI_SESSION_KEY " + cli() + " listen --bind 127.0.0.1 --port " +
                          std::to_string(hesai_test::free_udp_port()) + " --gps-port 0 --quiet --sensor 127.0.0.1 --ptc-port " +
                          std::to_string(unit.port()) + " --timeout 20 --seconds 60 2>" + err;
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(unit.accepted());  // it is connected and waits for the answer
  usleep(200000);
  const auto t0 = std::chrono::steady_clock::now();
  kill(pid, SIGINT);
  int status = 0;
  double took = -1;
  for (int i = 0; i < 25000; ++i) {  // 25 s at most
    if (waitpid(pid, &status, WNOHANG) == pid) {
      took = seconds_since(t0);
      break;
    }
    usleep(1000);
  }
  if (took < 0) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
  }
  const std::string text = read_text(err);
  std::remove(err.c_str());
  EXPECT_GE(took, 0.0) << "did not end";
  EXPECT_LT(took, 0.5 + kSlack) << text;
  EXPECT_TRUE(WIFEXITED(status)) << "ended by the signal, not by the program: " << text;
  EXPECT_NE(text.find("interrupted during the response header"), std::string::npos) << text;
}

}  // namespace
