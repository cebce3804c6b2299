package io.dtron.cli;

import io.dtron.engine.coverage.Coverage;
import java.io.IOException;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.Callable;
import picocli.CommandLine;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/** {@code dtron coverage merge A.json B.json ... [-o ALL.json]}: the coverage of many runs as one suite. */
@Command(name = "coverage", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1,
        exitCodeOnExecutionException = 1, subcommands = {CoverageCommand.Merge.class, CommandLine.HelpCommand.class},
        description = "Work with the coverage files of dtron run --coverage.")
final class CoverageCommand implements Callable<Integer> {
    @Spec
    private CommandSpec spec;

    @Override
    public Integer call() {
        spec.commandLine().usage(spec.commandLine().getErr());
        return 1;
    }

    /** Merges coverage files of one model. */
    @Command(name = "merge", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1,
            exitCodeOnExecutionException = 1,
            description = {"Merge the coverage files of runs of one model (many seeds, many strategies) into the"
                    + " coverage of the suite: an element is covered when some run covered it; channel counts add"
                    + " up. Prints the summary of the union.",
                    "A file given twice (or a copy of one) is refused: a run counts once.",
                    "Exit code 0 when merged, 1 when a file cannot be read, is given twice or is of another model."})
    static final class Merge implements Callable<Integer> {
        @Spec
        private CommandSpec spec;

        @Parameters(paramLabel = "FILE.json", arity = "1..*", description = "Coverage files of dtron run --coverage.")
        private List<Path> files;

        @Option(names = {"-o", "--output"}, paramLabel = "ALL.json", description = "Write the merged coverage here.")
        private Path output;

        @Override
        public Integer call() {
            PrintWriter out = spec.commandLine().getOut();
            PrintWriter err = spec.commandLine().getErr();
            try {
                List<Coverage> all = new ArrayList<>();
                List<String> texts = new ArrayList<>();
                for (Path f : files) {
                    String text;
                    String twice;
                    try {
                        text = Files.readString(f, StandardCharsets.UTF_8);
                        twice = givenBefore(f, text, texts);
                    } catch (IOException e) {
                        err.println("dtron coverage merge: cannot read " + f + ": " + OutputFile.reason(e));
                        return 1;
                    }
                    if (twice != null) {
                        err.println("dtron coverage merge: " + f + " " + twice + ": a run counts once in a suite");
                        return 1;
                    }
                    texts.add(text);
                    try {
                        all.add(CoverageJson.read(text));
                    } catch (IllegalArgumentException e) {
                        err.println("dtron coverage merge: " + f + ": " + e.getMessage());
                        return 1;
                    }
                }
                for (int i = 1; i < all.size(); i++) {
                    if (!all.get(i).fingerprint().equals(all.get(0).fingerprint())) {
                        err.println("dtron coverage merge: " + files.get(i) + " is the coverage of another model than "
                                + files.get(0) + " (" + all.get(i).model() + ", fingerprint "
                                + all.get(i).fingerprint() + ", not " + all.get(0).model() + ", fingerprint "
                                + all.get(0).fingerprint() + ")");
                        return 1;
                    }
                }
                Coverage union;
                try {
                    union = Coverage.union(all);
                } catch (IllegalArgumentException e) {
                    err.println("dtron coverage merge: " + e.getMessage());
                    return 1;
                }
                if (output != null) {
                    try {
                        Files.writeString(output, CoverageJson.write(union), StandardCharsets.UTF_8);
                    } catch (IOException e) {
                        err.println("dtron coverage merge: cannot write " + output + ": " + OutputFile.reason(e));
                        return 1;
                    }
                }
                out.println(union.summary());
                return 0;
            } finally {
                out.flush();
                err.flush();
            }
        }

        /**
         * How {@code file}, whose text is {@code text}, repeats one of the files before it ({@code texts}, in the
         * order of {@link #files}): the same file by another path, or a copy of one; null when it is new.
         */
        private String givenBefore(Path file, String text, List<String> texts) throws IOException {
            for (int i = 0; i < texts.size(); i++) {
                if (Files.isSameFile(file, files.get(i))) {
                    return "is given twice (as " + files.get(i) + " too)";
                }
                if (texts.get(i).equals(text)) {
                    return "is a copy of " + files.get(i);
                }
            }
            return null;
        }
    }
}
