/* The entry JupyterLab loads for the extension skilllib-book (package.json: jupyterlab._build.load).
 *
 * JupyterLab's federated-extension protocol (its staging/bootstrap.js and index.js): the script
 * defines a container window._JUPYTERLAB[name] with init(shareScope) and get(module), a promise of a
 * factory of the module, whose `default` is the list of plugins. JupyterLab serves an extension's
 * files as immutable (cached for a year), which is right for webpack's hashed names but not for a
 * hand-written script that changes with the repository: this entry never changes, and loads the
 * plugin (book.js, beside it) afresh on every page load. No build step, no network.
 */
(function () {
  "use strict";
  var NAME = "skilllib-book";
  var here = document.currentScript ? document.currentScript.src.replace(/[?#].*$/, "").replace(/[^/]*$/, "") : "";
  var loaded = new Promise(function (resolve, reject) {
    var script = document.createElement("script");
    script.src = here + "book.js?load=" + Date.now();
    script.onload = function () {
      if (window.SKILLLIB_BOOK_LAB) resolve(window.SKILLLIB_BOOK_LAB.plugin);
      else reject(new Error(NAME + ": book.js did not define its plugin"));
    };
    script.onerror = function () { reject(new Error(NAME + ": book.js could not be loaded")); };
    document.head.appendChild(script);
  });
  window._JUPYTERLAB = window._JUPYTERLAB || {};
  window._JUPYTERLAB[NAME] = {
    init: function () { return Promise.resolve(); },
    get: function () {
      return loaded.then(function (plugin) {
        return function () { return { __esModule: true, default: [plugin] }; };
      });
    }
  };
})();
