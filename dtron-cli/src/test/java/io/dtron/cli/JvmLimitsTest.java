package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import java.io.IOException;
import java.io.Writer;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * Models past the JVM's limits end every command with one line and exit code 1, never a stack trace: nesting
 * deeper than the front end's limit is a model error naming the file and the limit; a model too large for the
 * heap names the file, the heap limit and the {@code -Xmx} that loads it (in a JVM of its own with 64 MB).
 */
@Timeout(value = 180, unit = TimeUnit.SECONDS)
class JvmLimitsTest {
    private static final Duration WAIT = Duration.ofSeconds(150);

    @TempDir
    Path dir;

    private Path deepModel() throws IOException {
        Path model = dir.resolve("deep.xml");
        Files.writeString(model, "<nta><declaration>chan i_go, o_done;\nint x = " + "(".repeat(4000) + "1"
                + ")".repeat(4000) + ";</declaration>\n<template><name>P</name><location id=\"a\"/><init ref=\"a\"/>"
                + "</template>\n<system>system P;</system></nta>\n");
        return model;
    }

    @Test
    void fourThousandParenthesesAreAModelErrorNamingTheFileAndTheLimitInEveryCommand() throws IOException {
        Path model = deepModel();
        String error = model + ":2:1009: error: expression nested deeper than the limit of 1000 levels"
                + " (declaration, column 1009)";
        for (String[] args : List.of(new String[] {"check", model.toString()},
                new String[] {"run", model.toString(), "--sut", "io.dtron.cli.TickerForTests", "--virtual-time"},
                new String[] {"tron", "-I", "SocketAdapter", model.toString(), "--", "localhost", "1"})) {
            CommandRun r = CommandRun.of(args);
            assertEquals(1, r.exit(), args[0] + ": " + r.err());
            assertEquals(model + ": 1 error\n  " + error + "\n", r.err().replace(System.lineSeparator(), "\n"),
                    args[0]);
            assertFalse(r.out().contains("\tat ") || r.err().contains("\tat "), "no stack trace: " + r.err());
        }
    }

    /** A valid model of about {@code megabytes} MB: templates with located, labelled edges. */
    private Path largeModel(int megabytes) throws IOException {
        Path model = dir.resolve("large.xml");
        try (Writer w = Files.newBufferedWriter(model, StandardCharsets.UTF_8)) {
            w.write("<nta><declaration>int v; clock x;</declaration>\n");
            long size = 0;
            int t = 0;
            StringBuilder system = new StringBuilder("system ");
            while (size < (long) megabytes << 20) {
                StringBuilder sb = new StringBuilder("<template><name>T").append(t).append("</name>\n");
                for (int l = 0; l < 50; l++) {
                    sb.append("<location id=\"t").append(t).append('l').append(l).append("\" x=\"").append(l * 10)
                            .append("\" y=\"0\"><label kind=\"invariant\">x &lt;= ").append(100 + l)
                            .append("</label></location>\n");
                }
                sb.append("<init ref=\"t").append(t).append("l0\"/>\n");
                for (int l = 0; l < 50; l++) {
                    sb.append("<transition><source ref=\"t").append(t).append('l').append(l).append("\"/><target ref=\"t")
                            .append(t).append('l').append((l + 1) % 50).append("\"/><label kind=\"guard\">x &gt;= ")
                            .append(l).append(" &amp;&amp; v &lt; 1000</label><label kind=\"assignment\">v = (v + ")
                            .append(l).append(") % 1000, x = 0</label></transition>\n");
                }
                sb.append("</template>\n");
                system.append(t == 0 ? "" : ", ").append('T').append(t);
                w.write(sb.toString());
                size += sb.length();
                t++;
            }
            w.write("<system>" + system + ";</system></nta>\n");
        }
        return model;
    }

    @Test
    void aModelTooLargeForTheHeapIsOneLineWithTheHeapLimitAndTheXmxThatLoadsIt() throws Exception {
        Path model = largeModel(8);
        for (String command : List.of("check", "run")) {
            Path log = dir.resolve(command + ".log");
            String[] args = command.equals("check") ? new String[] {"check", model.toString()}
                    : new String[] {"run", model.toString(), "--sut", "io.dtron.cli.TickerForTests", "--virtual-time"};
            try (ChildJvm child = ChildJvm.start(List.of("-Xmx64m"), DtronCommand.class, log, args)) {
                assertEquals(1, child.waitFor(WAIT), child.output());
                String output = child.output();
                assertFalse(output.contains("\tat "), "no stack trace: " + output);
                assertFalse(output.contains("Exception") || output.contains("OutOfMemoryError"), output);
                List<String> lines = output.lines().toList();
                assertEquals(1, lines.size(), "one line: " + output);
                Matcher m = Pattern.compile("dtron " + command + ": " + Pattern.quote(model.toString())
                        + ": out of memory: loading the model takes more than the Java heap limit of 64 MB \\(about 20"
                        + " MB per MB of model\\); raise the limit, e\\.g\\. java -Xmx(\\d+)([mg]) -jar dtron\\.jar "
                        + command + " " + Pattern.quote(model.toString()) + ".*").matcher(lines.get(0));
                assertTrue(m.matches(), lines.get(0));
                long suggested = Long.parseLong(m.group(1)) * (m.group(2).equals("g") ? 1024 : 1);
                assertTrue(suggested >= 64 + 20 * 8, "enough for 8 MB of model: " + lines.get(0));
            }
        }
    }
}
