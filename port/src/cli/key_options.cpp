// Key material on the command line, in files and in the environment: the options that give the
// QT128's session key or secret, how they are read and how every copy is wiped.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "hesai/ct.h"
#include "hesai/hkdf.h"
#include "options.h"

extern char** environ;  // POSIX: the process's environment

namespace hesai::cli {

namespace {
// The key option given, read when all options are (finish_key_options).
enum class KeyOption : std::uint8_t { none, session_key, session_key_file, secret, secret_file };
struct PendingKey {
  KeyOption option = KeyOption::none;
  std::string value;  // the key in hex or the secret (wiped once used), or the key file's path
  std::string lidar_random, client_random;
};
PendingKey g_pending;

void wipe(std::string& s) { wipe_secret(s); }
}  // namespace

void wipe_secret(std::string& s) {
  s.resize(s.capacity());
  secure_wipe(&s[0], s.size());
  s.clear();
}

const char* const kKeyOptionsHelp =
    "  --session-key-file FILE QT128 signature key: 64 hex digits on the first line of FILE\n"
    "  --secret-file FILE --lidar-random HEX64 --client-random HEX64\n"
    "                          derive the session key by HKDF-SHA256 as the sensor does, from the\n"
    "                          secret on the first line of FILE\n"
    "  HESAI_SESSION_KEY, HESAI_SECRET  the same from the environment, when no key option is given\n"
    "  --session-key HEX64, --secret TEXT  the same on the command line, where other users can\n"
    "                          read them (ps): a warning; prefer the files or the environment\n"
    "  --allow-unsigned        with a key, accept packets that carry no signature\n";
bool parse_key_option(Args& args, std::string& error) {
  const std::string opt = args.peek();
  const auto need = [&](std::string& v) {
    args.take();
    if (!args.value(opt, v)) {
      error = opt + " needs a value";
      return false;
    }
    return true;
  };
  const KeyOption key = opt == "--session-key"        ? KeyOption::session_key
                        : opt == "--session-key-file" ? KeyOption::session_key_file
                        : opt == "--secret"           ? KeyOption::secret
                        : opt == "--secret-file"      ? KeyOption::secret_file
                                                      : KeyOption::none;
  if (key != KeyOption::none) {
    args.take();
    if (g_pending.option != KeyOption::none) {
      error = "one key at a time: --session-key-file, --secret-file, --session-key or --secret";
      return true;
    }
    g_pending.option = key;
    const bool on_command_line = key == KeyOption::session_key || key == KeyOption::secret;
    if (!(on_command_line ? args.secret_value(g_pending.value) : args.value(opt, g_pending.value)))
      error = opt + " needs a value";
    return true;
  }
  if (opt == "--lidar-random") return need(g_pending.lidar_random) || true;
  if (opt == "--client-random") return need(g_pending.client_random) || true;
  return false;
}

namespace {

// The first line of a key file, without its line feed (or CR LF), into `out`. Warns when group or
// others have any access to the file, as ssh does for a private key. Returns an exit status.
int read_key_file(const std::string& option, const std::string& path, std::string& out, std::string& error) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    error = option + ": cannot open '" + path + "': " + std::strerror(errno);
    return kExitInput;
  }
  struct stat st {};
  if (fstat(fd, &st) == 0 && (st.st_mode & 077) != 0)
    std::fprintf(stderr, "hesai: warning: key file '%s' is accessible by group or others (mode %04o): chmod 600 '%s'\n",
                 path.c_str(), static_cast<unsigned>(st.st_mode & 07777), path.c_str());
  char buf[256];  // a key line is 64 hex digits, a secret 8 to 32 characters
  std::size_t n = 0;
  int err = 0;
  while (n < sizeof buf) {
    const ssize_t k = ::read(fd, buf + n, sizeof buf - n);
    if (k > 0) n += static_cast<std::size_t>(k);
    else if (k == 0) break;
    else if (errno != EINTR) {
      err = errno;
      break;
    }
  }
  ::close(fd);
  const void* lf = std::memchr(buf, '\n', n);
  std::size_t len = lf != nullptr ? static_cast<std::size_t>(static_cast<const char*>(lf) - buf) : n;
  if (len > 0 && buf[len - 1] == '\r') --len;
  int status = kExitOk;
  if (err != 0) {
    error = option + ": cannot read '" + path + "': " + std::strerror(err);
    status = kExitInput;
  } else if (lf == nullptr && n == sizeof buf) {
    error = option + ": the first line of '" + path + "' is longer than any key";
    status = kExitUsage;
  } else {
    out.assign(buf, len);
  }
  secure_wipe(buf, sizeof buf);
  return status;
}

// Removes the variable `name` from the environment once its value is read, its bytes wiped in place
// first: unsetenv alone drops the pointer, and /proc/PID/environ (the environment the process
// started with) would still show it, as would the memory of a later crash dump.
void scrub_env(const char* name) {
  const std::size_t len = std::strlen(name);
  std::vector<char*> entries;
  for (char** e = environ; e != nullptr && *e != nullptr; ++e)
    if (std::strncmp(*e, name, len) == 0 && (*e)[len] == '=') entries.push_back(*e);
  unsetenv(name);
  for (char* entry : entries) secure_wipe(entry, std::strlen(entry));
}

// Where the key came from, for messages; the option or variable that carried it.
const char* key_source_name(KeyOption k, bool from_environment) {
  if (from_environment) return k == KeyOption::session_key ? "HESAI_SESSION_KEY" : "HESAI_SECRET";
  switch (k) {
    case KeyOption::session_key: return "--session-key";
    case KeyOption::session_key_file: return "--session-key-file";
    case KeyOption::secret: return "--secret";
    case KeyOption::secret_file: return "--secret-file";
    case KeyOption::none: break;
  }
  return "";
}

// `key_text` (64 hex digits or a secret) to the session key of `o`. Returns an exit status.
int set_key(KeyOption kind, const char* source, const std::string& key_text, DecodeOptions& o, std::string& error) {
  const PendingKey& p = g_pending;
  const bool secret = kind == KeyOption::secret || kind == KeyOption::secret_file;
  if (!secret) {
    if (!p.lidar_random.empty() || !p.client_random.empty()) {
      error = "--lidar-random and --client-random go with a secret (--secret-file, HESAI_SECRET), not with " +
              std::string(source);
      return kExitUsage;
    }
    if (!parse_hex(key_text, o.session_key.data(), 32)) {
      error = std::string(source) + " takes 64 hex digits (32 bytes)";
      return kExitUsage;
    }
    o.has_key = true;
    return kExitOk;
  }
  if (o.session_secret_allowed && p.lidar_random.empty() && p.client_random.empty()) {
    if (key_text.size() < kHesaiSecretMin || key_text.size() > kHesaiSecretMax) {
      error = std::string(source) + ": the secret must be 8 to 32 characters";
      return kExitUsage;
    }
    o.session_secret = key_text;  // the session's randoms come from the sensor
    return kExitOk;
  }
  std::uint8_t lidar[32], client[32];
  if (!parse_hex(p.lidar_random, lidar, 32) || !parse_hex(p.client_random, client, 32)) {
    error = std::string(source) + " needs --lidar-random HEX64 and --client-random HEX64 (32 bytes each in hex)";
    return kExitUsage;
  }
  const ByteView text{reinterpret_cast<const std::uint8_t*>(key_text.data()), key_text.size()};
  if (hesai_session_key(text, lidar, client, o.session_key.data()) != Error::ok) {
    error = std::string(source) + ": the secret must be 8 to 32 characters";
    return kExitUsage;
  }
  o.has_key = true;
  return kExitOk;
}

}  // namespace

int finish_key_options(DecodeOptions& o, std::string& error) {
  PendingKey& p = g_pending;
  KeyOption kind = p.option;
  bool from_environment = false;
  std::string text;  // the key in hex or the secret
  int status = kExitOk;
  if (kind == KeyOption::session_key || kind == KeyOption::secret) {
    std::fprintf(stderr, "hesai: warning: %s puts key material on the command line, where other users of this "
                         "machine can read it (ps, /proc/PID/cmdline, shell history); use %s FILE or %s instead\n",
                 key_source_name(kind, false), kind == KeyOption::secret ? "--secret-file" : "--session-key-file",
                 kind == KeyOption::secret ? "HESAI_SECRET" : "HESAI_SESSION_KEY");
    text.swap(p.value);
  } else if (kind != KeyOption::none) {
    status = read_key_file(key_source_name(kind, false), p.value, text, error);
  } else {
    // No key option: the environment. An empty variable counts as unset.
    const char* env_key = std::getenv("HESAI_SESSION_KEY");
    const char* env_secret = std::getenv("HESAI_SECRET");
    const bool has_env_key = env_key != nullptr && *env_key != '\0';
    const bool has_env_secret = env_secret != nullptr && *env_secret != '\0';
    if (has_env_key && has_env_secret) {
      error = "HESAI_SESSION_KEY and HESAI_SECRET are both set: unset one, or give a key option (which takes precedence)";
      status = kExitUsage;
    } else if (has_env_key || has_env_secret) {
      kind = has_env_key ? KeyOption::session_key : KeyOption::secret;
      from_environment = true;
      text.assign(has_env_key ? env_key : env_secret);
    }
    scrub_env("HESAI_SESSION_KEY");  // read: neither stays in the environment
    scrub_env("HESAI_SECRET");
  }
  if (status == kExitOk && kind != KeyOption::none) {
    status = set_key(kind, key_source_name(kind, from_environment), text, o, error);
  } else if (status == kExitOk && (!p.lidar_random.empty() || !p.client_random.empty())) {
    error = "--lidar-random and --client-random go with a secret: --secret-file FILE or HESAI_SECRET";
    status = kExitUsage;
  }
  wipe(text);
  wipe(p.value);
  p = PendingKey{};
  return status;
}

void wipe_key(DecodeOptions& o) {
  secure_wipe(o.session_key.data(), o.session_key.size());
  wipe(o.session_secret);
}

int read_secret(const std::string& secret_file, std::string& secret, std::string& error) {
  int status = kExitOk;
  if (!secret_file.empty()) {
    status = read_key_file("--secret-file", secret_file, secret, error);
  } else if (const char* env = std::getenv("HESAI_SECRET"); env != nullptr && *env != '\0') {
    secret.assign(env);
    scrub_env("HESAI_SECRET");
  } else {
    error = "a signature session needs the shared secret: --secret-file FILE or HESAI_SECRET";
    return kExitUsage;
  }
  if (status == kExitOk && (secret.size() < kHesaiSecretMin || secret.size() > kHesaiSecretMax)) {
    error = std::string(secret_file.empty() ? "HESAI_SECRET" : "--secret-file") + ": the secret must be 8 to 32 characters";
    status = kExitUsage;
  }
  if (status != kExitOk) wipe(secret);
  return status;
}

}  // namespace hesai::cli
