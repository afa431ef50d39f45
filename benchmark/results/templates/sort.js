// Click a heading to sort its table by that column; click again to reverse. Numeric cells sort
// by data-value, "n/a" cells (empty data-value) always last. Inlined into index.html.
document.querySelectorAll("table.sortable").forEach(function (table) {
  function key(cell) {
    var v = cell.getAttribute("data-value");
    if (v === null) return cell.textContent;
    return v === "" ? null : parseFloat(v);
  }
  table.querySelectorAll("th").forEach(function (th) {
    th.addEventListener("click", function () {
      var col = th.cellIndex, body = table.tBodies[0];
      var asc = th.getAttribute("aria-sort") !== "ascending";
      table.querySelectorAll("th").forEach(function (h) { h.removeAttribute("aria-sort"); });
      th.setAttribute("aria-sort", asc ? "ascending" : "descending");
      var rows = Array.prototype.slice.call(body.rows);
      rows.sort(function (a, b) {
        var x = key(a.cells[col]), y = key(b.cells[col]);
        if (x === null || y === null) return (x === null) - (y === null);
        var c = typeof x === "number" ? x - y : String(x).localeCompare(String(y));
        return asc ? c : -c;
      });
      rows.forEach(function (r) { body.appendChild(r); });
    });
  });
});
