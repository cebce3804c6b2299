package io.dtron.cli;

import java.io.IOException;
import java.nio.charset.CharacterCodingException;
import java.nio.file.AccessDeniedException;
import java.nio.file.FileSystemException;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;

/**
 * The checks of a file a command writes ({@code --junit}, {@code --alarms}, {@code --trace}, ...), made before the
 * command does its work, so that a run's result is not lost to a file that cannot be written and no input is
 * overwritten; and the reason of a failed read or write in words, without the exception's class.
 */
final class OutputFile {
    private OutputFile() {
    }

    /**
     * Why {@code option FILE} cannot be written, or null when it can: an empty name, a folder, a folder that does not
     * exist, no permission to write, or one of the command's {@code inputs} (the model, the trace), which it would
     * overwrite. Null when the option was not given ({@code file} null).
     */
    static String problem(String option, Path file, Path... inputs) {
        if (file == null) {
            return null;
        }
        if (file.toString().isEmpty()) {
            return option + ": give a file name";
        }
        if (Files.isDirectory(file)) {
            return option + " " + file + ": is a folder; give a file in it";
        }
        Path folder = file.toAbsolutePath().getParent();
        if (folder == null || !Files.isDirectory(folder)) {
            return option + " " + file + ": the folder " + folder + " does not exist";
        }
        if (Files.exists(file) ? !Files.isWritable(file) : !Files.isWritable(folder)) {
            return option + " " + file + ": cannot be written (permission denied)";
        }
        for (Path input : inputs) {
            if (input != null && same(file, input)) {
                return option + " " + file + ": is the command's input " + input + ", which writing would destroy";
            }
        }
        return null;
    }

    /** Why {@code file}, an input, cannot be read, or null when it can. */
    static String unreadable(Path file) {
        if (!Files.exists(file)) {
            return "no such file";
        }
        if (Files.isDirectory(file)) {
            return "is a folder";
        }
        return Files.isReadable(file) ? null : "permission denied";
    }

    /** The reason of {@code e} in words: no exception class, the file named once. */
    static String reason(IOException e) {
        if (e instanceof CharacterCodingException) {
            return "not UTF-8 text";
        }
        if (e instanceof NoSuchFileException) {
            return "no such file";
        }
        if (e instanceof AccessDeniedException) {
            return "permission denied";
        }
        if (e instanceof FileSystemException f && f.getReason() != null) {
            return f.getReason();
        }
        String message = e.getMessage() != null ? e.getMessage() : "input or output error";
        // a wrapped exception's message starts with the class of the one it wraps: "java.io.IOException: ..."
        return message.replaceFirst("^([a-z][a-z0-9_]*\\.)+[A-Z][A-Za-z0-9_$]*: ", "");
    }

    private static boolean same(Path a, Path b) {
        try {
            if (Files.exists(a) && Files.exists(b)) {
                return Files.isSameFile(a, b);
            }
        } catch (IOException e) {
            // compared by name below
        }
        return a.toAbsolutePath().normalize().equals(b.toAbsolutePath().normalize());
    }
}
