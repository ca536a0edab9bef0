// The search box: results of MiniSearch over the index that render.mjs writes (search-index.js sets
// window.BOOK_SEARCH; a <script>, since fetch() of file:// is blocked).
(function () {
  'use strict';
  // ---- search ------------------------------------------------------------------------------------
  var input = document.getElementById('search-input');
  var list = document.getElementById('search-results');
  var data = window.BOOK_SEARCH;
  if (!input || !data || !window.MiniSearch) return;
  var mini = window.MiniSearch.loadJS(data.index, data.options);
  var searchOptions = { prefix: true, fuzzy: 0.2, combineWith: 'AND', boost: { page: 3, section: 2 } };

  function show(query) {
    list.textContent = '';
    var results = query.trim().length < 2 ? [] : mini.search(query, searchOptions).slice(0, 12);
    if (!results.length) {
      if (query.trim().length >= 2) {
        var none = document.createElement('li');
        none.className = 'search-none';
        none.textContent = 'Nothing found for “' + query.trim() + '”.';
        list.appendChild(none);
      }
      list.hidden = query.trim().length < 2;
      return;
    }
    results.forEach(function (r) {
      var li = document.createElement('li');
      var a = document.createElement('a');
      a.href = r.url;
      a.className = 'search-result';
      var page = document.createElement('span');
      page.className = 'search-page';
      page.textContent = r.page;
      a.appendChild(page);
      if (r.section) {
        var sec = document.createElement('span');
        sec.className = 'search-section';
        sec.textContent = r.section;
        a.appendChild(sec);
      }
      li.appendChild(a);
      list.appendChild(li);
    });
    list.hidden = false;
  }

  input.addEventListener('input', function () { show(input.value); });
  input.addEventListener('keydown', function (e) {
    if (e.key === 'Enter') {
      var first = list.querySelector('a');
      if (first) window.location.href = first.href;
    } else if (e.key === 'Escape') {
      input.value = '';
      show('');
    }
  });
})();
