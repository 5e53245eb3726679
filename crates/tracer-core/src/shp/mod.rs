pub mod description;
