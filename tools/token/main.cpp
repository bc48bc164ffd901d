// SPDX-License-Identifier: MIT
// rewind-token: what a match backend does for secure connections.
//   keygen  a new server key (64 hex digits), shared with rewind-server
//   mint    a connect token for one client and slot, as one hex line
//   inspect what a token says in the clear (never its keys)
//   api-key a bearer key for the server's HTTP endpoints, added to a keys file
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "rewind/cli/flag_parser.h"
#include "rewind/net/connect_token.h"

namespace {

using namespace rwd;

constexpr const char* kUsage =
    "rewind-token keygen|mint|inspect|api-key [flags]\n"
    "  keygen  --out FILE            write a new server key (refuses to overwrite)\n"
    "  mint    --key-file FILE --match ID --slot N --client-id N [--expires-in S] [--out FILE]\n"
    "  inspect --token-file FILE | --token HEX\n"
    "  api-key --name NAME --keys FILE [--admin]  add a bearer key for the HTTP endpoints\n"
    "A token connects once. For a client that comes back (a new process, a lost\n"
    "connection), mint a fresh token with the same --client-id and --slot; the server\n"
    "takes it once it has dropped the old connection (--peer-timeout).\n";

Result<std::string> read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::Error(ErrorCode::kIo, "cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Writes `text` to a new file readable by its owner only (keys and tokens
// are secrets); refuses to replace an existing one.
Status write_secret(const std::string& path, const std::string& text) {
  if (std::filesystem::exists(path)) {
    return Status::Error(ErrorCode::kInvalidArgument, path + " exists; not overwritten");
  }
  {
    std::ofstream out(path, std::ios::binary);
    if (!out) return Status::Error(ErrorCode::kIo, "cannot write " + path);
    out << text;
    if (!out.flush()) return Status::Error(ErrorCode::kIo, "cannot write " + path);
  }
  std::error_code ec;
  std::filesystem::permissions(
      path, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write, ec);
  return Status::Ok();
}

int64_t now_unix() {
  return std::chrono::duration_cast<std::chrono::seconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

int fail(const std::string& command, const Status& status) {
  std::cerr << "rewind-token " << command << ": " << status.message() << "\n";
  return 1;
}

int keygen(int argc, const char* const* argv) {
  std::string out;
  cli::FlagParser flags("rewind-token keygen", "rewind-token keygen --out FILE",
                        "Writes a new random 32-byte server key as 64 hex digits.");
  flags.add_string("out", &out, "file to create (mode 0600)");
  if (Status s = flags.parse(argc, argv, 2); !s.ok()) return fail("keygen", s), cli::kExitUsage;
  if (flags.help_requested()) return std::cout << flags.help_text(), 0;
  if (out.empty())
    return fail("keygen", Status::Error(ErrorCode::kInvalidArgument, "--out is required")),
           cli::kExitUsage;
  const net::Key key = net::generate_key();
  if (Status s = write_secret(out, net::to_hex(key) + "\n"); !s.ok()) return fail("keygen", s);
  std::cout << "wrote a new server key to " << out << "\n";
  return 0;
}

// Appends "NAME KEY [admin]" to a keys file (rewind-server --control-keys,
// --metrics-keys), creating it owner-only; prints the key for the caller.
int api_key(int argc, const char* const* argv) {
  std::string name, keys_file;
  bool admin = false;
  cli::FlagParser flags("rewind-token api-key", "rewind-token api-key --name NAME --keys FILE",
                        "Adds a caller with a new random bearer key (64 hex digits) to FILE, "
                        "one 'NAME KEY [admin]' a line,\nand prints the key: the caller sends "
                        "'Authorization: Bearer KEY'.");
  flags.add_string("name", &name, "the caller's name (A-Z a-z 0-9 . _ -, at most 64)");
  flags.add_string("keys", &keys_file, "keys file to add to (created mode 0600 if missing)");
  flags.add_bool("admin", &admin, "the caller may stop any match, not only its own");
  if (Status s = flags.parse(argc, argv, 2); !s.ok()) return fail("api-key", s), cli::kExitUsage;
  if (flags.help_requested()) return std::cout << flags.help_text(), 0;
  const bool name_ok = !name.empty() && name.size() <= 64 &&
                       name.find_first_not_of(
                           "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                           "0123456789._-") == std::string::npos;
  if (!name_ok || keys_file.empty()) {
    return fail("api-key", Status::Error(ErrorCode::kInvalidArgument,
                                         "--name (A-Z a-z 0-9 . _ -) and --keys are required")),
           cli::kExitUsage;
  }
  std::string existing;
  if (std::filesystem::exists(keys_file)) {
    Result<std::string> text = read_text(keys_file);
    if (!text.ok()) return fail("api-key", text.status());
    existing = *text;
    std::istringstream lines(existing);
    for (std::string line; std::getline(lines, line);) {
      std::istringstream words(line);
      std::string first;
      if (words >> first && first == name) {
        return fail("api-key", Status::Error(ErrorCode::kInvalidArgument,
                                             "'" + name + "' is already in " + keys_file));
      }
    }
  }
  const std::string key = net::to_hex(net::generate_key());
  const std::string line = name + " " + key + (admin ? " admin" : "") + "\n";
  if (existing.empty()) {
    if (Status s = write_secret(keys_file, line); !s.ok()) return fail("api-key", s);
  } else {
    std::ofstream out(keys_file, std::ios::binary | std::ios::app);
    if (!existing.ends_with('\n')) out << "\n";
    out << line;
    if (!out.flush()) {
      return fail("api-key", Status::Error(ErrorCode::kIo, "cannot write " + keys_file));
    }
  }
  std::cout << key << "\n";
  return 0;
}

int mint(int argc, const char* const* argv) {
  std::string key_file, match, out;
  int64_t slot = -1, client_id = 0, expires_in = 3600;
  cli::FlagParser flags(
      "rewind-token mint", "rewind-token mint --key-file FILE --match ID --slot N --client-id N",
      "Mints a connect token for one client: prints it as one hex line, or writes it to --out.\n"
      "A token connects once: the server remembers it until it expires and refuses it again,\n"
      "copies included. For a client that comes back (a new process, a lost connection), mint\n"
      "a fresh token with the same --client-id and --slot: the server ignores it while that\n"
      "client is still connected and takes it once the match has dropped the old connection\n"
      "(rewind-server --peer-timeout). A token for another client id takes the slot only\n"
      "then, too: it never cuts a connected holder off.");
  flags.add_string("key-file", &key_file, "the server key (rewind-token keygen)");
  flags.add_string("match", &match, "the match id the server runs (--match-id)");
  flags.add_int("slot", &slot, 0, 63, "the player slot the token takes");
  flags.add_int("client-id", &client_id, 1, INT64_MAX, "the backend's id of the client");
  flags.add_int("expires-in", &expires_in, 1, net::kMaxTokenLifetimeS,
                "seconds the token is valid");
  flags.add_string("out", &out, "file to create (mode 0600) instead of printing");
  if (Status s = flags.parse(argc, argv, 2); !s.ok()) return fail("mint", s), cli::kExitUsage;
  if (flags.help_requested()) return std::cout << flags.help_text(), 0;
  if (key_file.empty() || match.empty() || slot < 0 || client_id == 0) {
    return fail("mint", Status::Error(ErrorCode::kInvalidArgument,
                                      "--key-file, --match, --slot and --client-id are required")),
           cli::kExitUsage;
  }
  Result<std::string> text = read_text(key_file);
  if (!text.ok()) return fail("mint", text.status());
  Result<net::Key> key = net::key_from_hex(*text);
  if (!key.ok())
    return fail("mint",
                Status::Error(ErrorCode::kCorrupt, key_file + ": " + key.status().message()));
  const int64_t now = now_unix();
  Result<net::ConnectToken> token =
      net::make_connect_token(*key, match, static_cast<uint32_t>(slot),
                              static_cast<uint64_t>(client_id), now + expires_in, now);
  if (!token.ok()) return fail("mint", token.status());
  const std::string hex = net::to_hex(net::write_connect_token(*token)) + "\n";
  if (out.empty()) {
    std::cout << hex;
    return 0;
  }
  if (Status s = write_secret(out, hex); !s.ok()) return fail("mint", s);
  std::cout << "wrote a token for slot " << slot << " of '" << match << "' to " << out << "\n";
  return 0;
}

int inspect(int argc, const char* const* argv) {
  std::string token_file, token_hex;
  cli::FlagParser flags("rewind-token inspect", "rewind-token inspect --token-file FILE",
                        "Prints what a connect token says in the clear (never its keys).");
  flags.add_string("token-file", &token_file, "a token file (rewind-token mint --out)");
  flags.add_string("token", &token_hex, "a token as hex");
  if (Status s = flags.parse(argc, argv, 2); !s.ok()) return fail("inspect", s), cli::kExitUsage;
  if (flags.help_requested()) return std::cout << flags.help_text(), 0;
  if (token_file.empty() == token_hex.empty()) {
    return fail("inspect",
                Status::Error(ErrorCode::kInvalidArgument, "give one of --token-file and --token")),
           cli::kExitUsage;
  }
  if (!token_file.empty()) {
    Result<std::string> text = read_text(token_file);
    if (!text.ok()) return fail("inspect", text.status());
    token_hex = *text;
  }
  Result<std::vector<uint8_t>> bytes = net::from_hex(token_hex);
  if (!bytes.ok()) return fail("inspect", bytes.status());
  Result<net::ConnectToken> token = net::read_connect_token(*bytes);
  if (!token.ok()) return fail("inspect", token.status());
  const int64_t left = token->expiry_unix_s - now_unix();
  std::cout << "slot " << token->slot << "\nclient id " << token->client_id << "\nmatch tag "
            << std::hex << token->match_tag << std::dec << "\nexpires " << token->expiry_unix_s
            << " (" << (left > 0 ? "in " + std::to_string(left) + " s" : "expired") << ")\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "keygen") return keygen(argc, argv);
  if (command == "mint") return mint(argc, argv);
  if (command == "inspect") return inspect(argc, argv);
  if (command == "api-key") return api_key(argc, argv);
  if (command == "--help" || command == "-h") return std::cout << kUsage, 0;
  std::cerr << (command.empty() ? "rewind-token: no command\n"
                                : "rewind-token: unknown command '" + command + "'\n")
            << kUsage;
  return rwd::cli::kExitUsage;
}
