package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.fail;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.regex.Pattern;

/**
 * A page of the user documentation ({@code src/site/markdown/NAME}) and its fenced code blocks, so that tests run
 * the code the page shows instead of a copy of it: the one place that reads a page's blocks, for every module's
 * tests (they run in the module's folder, beside the site's).
 */
public final class DocPage {
    /** The site's markdown folder, from the dtron-cli module folder the tests run in. */
    public static final Path SITE = Path.of("..", "src", "site", "markdown");

    /**
     * A fenced code block.
     *
     * @param info the word after the opening fence ({@code java}, {@code xml}, or empty)
     * @param code the lines between the fences, each ending with a newline
     * @param line the 1-based line of the opening fence
     */
    public record Block(String info, String code, int line) {
    }

    private final Path file;
    private final List<String> lines;
    private final List<Block> blocks = new ArrayList<>();

    private DocPage(Path file, List<String> lines) {
        this.file = file;
        this.lines = lines;
        Block open = null;
        StringBuilder code = new StringBuilder();
        for (int i = 0; i < lines.size(); i++) {
            String line = lines.get(i);
            if (open == null && line.startsWith("```")) {
                open = new Block(line.substring(3).trim(), "", i + 1);
                code.setLength(0);
            } else if (open != null && line.equals("```")) {
                blocks.add(new Block(open.info(), code.toString(), open.line()));
                open = null;
            } else if (open != null) {
                code.append(line).append('\n');
            }
        }
        if (open != null) {
            fail(file + ": the code block opened on line " + open.line() + " is never closed");
        }
    }

    /** Reads {@code src/site/markdown/NAME}. */
    public static DocPage read(String name) throws IOException {
        return read(SITE.resolve(name));
    }

    /** Reads a markdown file. */
    public static DocPage read(Path file) throws IOException {
        return new DocPage(file, Files.readAllLines(file));
    }

    /** The whole page. */
    public String text() {
        return String.join("\n", lines);
    }

    /** The page's fenced code blocks, in order. */
    public List<Block> blocks() {
        return List.copyOf(blocks);
    }

    /** The code of the blocks opened with {@code ```info}, in order. */
    public List<String> blocks(String info) {
        return blocks.stream().filter(b -> b.info().equals(info)).map(Block::code).toList();
    }

    /**
     * The code of the one block opened with {@code ```info} that contains {@code text} (a {@code pom.xml}: "xml" and
     * "<project"); fails the test if there is none or more.
     */
    public String block(String info, String text) {
        List<String> found = blocks(info).stream().filter(code -> code.contains(text)).toList();
        if (found.size() != 1) {
            fail(file + " should have one ```" + info + " block containing '" + text + "', but has " + found.size());
        }
        return found.get(0);
    }

    /** The one {@code java} block that declares class {@code simpleName}; fails the test if there is none or more. */
    public String javaClass(String simpleName) {
        Pattern declaration = Pattern.compile("(?m)^public (final )?class " + Pattern.quote(simpleName) + "\\b");
        List<Block> found = blocks.stream()
                .filter(b -> b.info().equals("java") && declaration.matcher(b.code()).find())
                .toList();
        if (found.size() != 1) {
            fail(file + " should have one ```java block declaring 'public class " + simpleName + "', but has "
                    + found.size());
        }
        return found.get(0).code();
    }

    /**
     * The first code block after the first line that contains {@code text}; fails the test if the page has no
     * such line or no block after it.
     */
    public Block blockAfter(String text) {
        for (int i = 0; i < lines.size(); i++) {
            if (lines.get(i).contains(text)) {
                int markerLine = i + 1;
                return blocks.stream()
                        .filter(b -> b.line() > markerLine)
                        .findFirst()
                        .orElseThrow(() -> new AssertionError(file + ": no code block after '" + text + "'"));
            }
        }
        throw new AssertionError(file + " has no line containing '" + text + "'");
    }

    /** The blocks whose first line starts with {@code prefix} (a shell session: {@code "$ java"}). */
    public List<Block> blocksStartingWith(String prefix) {
        return blocks.stream().filter(b -> b.code().startsWith(prefix)).toList();
    }

    @Override
    public String toString() {
        return file.toString();
    }
}
