// Starts `lmdc lsp` for .lmd files: the compiler itself answers, so the
// diagnostics, hover and completion are the ones `lmdc check` gives.
const vscode = require("vscode");
const { LanguageClient, TransportKind } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const command = vscode.workspace.getConfiguration("lmd").get("server.path") || "lmdc";
  const server = { command, args: ["lsp"], transport: TransportKind.stdio };
  client = new LanguageClient(
    "lmd",
    "lmdc language server",
    { run: server, debug: server },
    { documentSelector: [{ scheme: "file", language: "lmd" }, { scheme: "untitled", language: "lmd" }] }
  );
  context.subscriptions.push(client);
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
