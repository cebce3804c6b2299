package io.dtron.report;

import java.io.IOException;
import java.io.InputStream;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;

/**
 * The report: one self-contained HTML page (its script and style inline, nothing fetched from a network) that
 * draws a run from its data, a {@link RunRecord#json()} block. The same page is the live view's, which fetches the
 * data and its updates from the server that serves it ({@link LiveView}).
 */
public final class ReportPage {
    private static final String TEMPLATE = load();
    private static final String DATA = "/*DATA*/null";

    private ReportPage() {
    }

    /** The page showing {@code record} as it is now. */
    public static String html(RunRecord record) {
        return withData(record.json());
    }

    /** Writes the page of {@code record} to {@code file}. */
    public static void write(RunRecord record, Path file) throws IOException {
        Files.writeString(file, html(record), StandardCharsets.UTF_8);
    }

    /** The live view's page: without data; its script fetches them and follows the updates. */
    static String live() {
        return TEMPLATE.replace(DATA, "{\"live\":true}");
    }

    private static String withData(String json) {
        int at = TEMPLATE.indexOf(DATA);
        return new StringBuilder(TEMPLATE.length() + json.length()).append(TEMPLATE, 0, at).append(json)
                .append(TEMPLATE, at + DATA.length(), TEMPLATE.length()).toString();
    }

    private static String load() {
        try (InputStream in = ReportPage.class.getResourceAsStream("report.html")) {
            if (in == null) {
                throw new IllegalStateException("report.html is missing from the dtron-report jar");
            }
            String page = new String(in.readAllBytes(), StandardCharsets.UTF_8);
            if (!page.contains(DATA)) {
                throw new IllegalStateException("report.html has no data block");
            }
            return page;
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }
}
