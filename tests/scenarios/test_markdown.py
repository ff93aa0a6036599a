"""The notes' Markdown subset as HTML: paragraphs, headings, lists, tables, code, and everything escaped."""

from shintai.scenarios.markdown import inline, to_html


def test_inline_formatting_and_escaping():
    assert inline("a **b** *c* `d*e*` [f](https://x.org)") == (
        'a <strong>b</strong> <em>c</em> <code>d*e*</code> <a href="https://x.org">f</a>')
    assert inline("<b>x</b> & 2 * 3 * 4") == "&lt;b&gt;x&lt;/b&gt; &amp; 2 * 3 * 4"
    assert "href" not in inline("[x](javascript:alert(1))")


def test_blocks():
    text = "# Title\n\nfirst line\nsecond line\n\n- one\n  more\n- two\n\n1. a\n2. b\n\n```\n<x> *y*\n```\n\n| a | b |\n|---|---|\n| 1 | 2 |"
    assert to_html(text).split("\n") == [
        "<h3>Title</h3>", "<p>first line second line</p>", "<ul><li>one more</li><li>two</li></ul>",
        "<ol><li>a</li><li>b</li></ol>", "<pre><code>&lt;x&gt; *y*</code></pre>",
        '<table class="md"><tr><th>a</th><th>b</th></tr><tr><td>1</td><td>2</td></tr></table>']


def test_a_line_that_starts_like_a_heading_is_text():
    """'#11' opens a paragraph (the snake's notes cite spec checks so); it once looped forever."""
    assert to_html("#11 of the spec\nholds.\n\nnext") == "<p>#11 of the spec holds.</p>\n<p>next</p>"
