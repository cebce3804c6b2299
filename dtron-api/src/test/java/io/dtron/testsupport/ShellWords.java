package io.dtron.testsupport;

import java.io.File;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

/** The words of a page's shell command lines, and the lines a command printed, for tests that run a page's sessions. */
public final class ShellWords {
    private ShellWords() {
    }

    /** The words of a shell command line, with '...' and "..." quoting. */
    public static List<String> split(String line) {
        List<String> words = new ArrayList<>();
        StringBuilder word = null;
        char quote = 0;
        for (char c : line.toCharArray()) {
            if (quote != 0) {
                if (c == quote) {
                    quote = 0;
                } else {
                    word.append(c);
                }
            } else if (c == '\'' || c == '"') {
                quote = c;
                word = word == null ? new StringBuilder() : word;
            } else if (Character.isWhitespace(c)) {
                if (word != null) {
                    words.add(word.toString());
                    word = null;
                }
            } else {
                word = word == null ? new StringBuilder() : word;
                word.append(c);
            }
        }
        if (word != null) {
            words.add(word.toString());
        }
        return words;
    }

    /** The lines of a command's output, with the folder {@code dir} taken out of file names. */
    public static List<String> lines(String text, Path dir) {
        return text.replace(dir + File.separator, "").lines().toList();
    }
}
